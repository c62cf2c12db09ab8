#include "identification/fit_spec.h"

#include <algorithm>
#include <filesystem>

#include "kinds/standard_kinds.h"
#include "sim/config/config_node.h"
#include "sweep/sweep_spec.h"

namespace tcpmsim::fit {

namespace {

// A YAML single-quoted scalar: any path, whatever characters it holds.
std::string single_quoted(const std::string& text) {
  std::string quoted = "'";
  for (char c : text) {
    if (c == '\'') quoted.push_back('\'');
    quoted.push_back(c);
  }
  return quoted + "'";
}

TimeWindow read_window(const ConfigNode& root, std::string_view key, const MeasuredData& data) {
  const auto [from, to] = root.interval(key, "s");
  const double first = data.time().front(), last = data.time().back();
  if (from < first || to > last) {
    root.at(key).fail("the window [" + seconds_text(from) + ", " + seconds_text(to) +
                      "] is not inside the data, which run from " + seconds_text(first) + " to " +
                      seconds_text(last));
  }
  return {from, to};
}

// The file `key` names, beside the fit file; fails at `key` when there is none.
std::string existing_file(const ConfigNode& root, std::string_view key, std::string_view what) {
  const std::string file = file_named_by(root.at(key));
  if (!std::filesystem::is_regular_file(file))
    root.at(key).fail("no " + std::string(what) + " file '" + file + "'");
  return file;
}

// Fails at `key` when its window holds fewer than `minimum` of the data's samples.
void require_samples(const ConfigNode& root, std::string_view key, const TimeWindow& window,
                     const MeasuredData& data, std::size_t minimum, std::string_view needed_for) {
  if (const std::string problem = window_samples_problem(data, window, minimum, needed_for);
      !problem.empty())
    root.at(key).fail(problem);
}

std::vector<FitOutput> read_outputs(const ConfigNode& root, const Scenario& model,
                                    const MeasuredData& data) {
  std::vector<FitOutput> outputs;
  const ConfigNode list = root.at("outputs");
  if (list.elements().empty()) list.fail("expected at least one output to compare");
  for (const ConfigNode& entry : list.elements()) {
    entry.declare({"channel", "output", "noise"});
    FitOutput output;
    output.channel = entry.text("channel");
    for (const FitOutput& earlier : outputs)
      if (earlier.channel == output.channel)
        entry.at("channel").fail("channel '" + output.channel + "' is compared twice");
    output.output = entry.text("output");
    output.unit = named_output(*model.system, entry.at("output"), "model").unit;
    const MeasuredChannel* channel = data.find(output.channel);
    if (!channel) entry.at("channel").fail(data.missing_channel(output.channel));
    if (!root.units().convertible(channel->unit, output.unit) ||
        root.units().convert(1.0, channel->unit, output.unit) != 1.0) {
      entry.at("channel").fail("channel '" + output.channel + "' is in " + channel->unit +
                               " and output '" + output.output + "' in " + output.unit);
    }
    output.noise = entry.difference("noise", output.unit, ValueCheck::positive());
    outputs.push_back(output);
  }
  return outputs;
}

std::vector<FitParameter> read_parameters(const ConfigNode& root, const Scenario& model) {
  std::vector<FitParameter> parameters;
  const ConfigNode list = root.at("parameters");
  if (list.elements().empty()) list.fail("expected at least one parameter to fit");
  const Context context = model.make_context();
  for (const ConfigNode& entry : list.elements()) {
    entry.declare({"path", "bounds"});
    FitParameter parameter;
    parameter.path = entry.text("path");
    const auto index = model.system->parameter_index(parameter.path);
    if (!index) entry.at("path").fail("the model has no parameter '" + parameter.path + "'");
    const auto& info = model.system->parameters()[static_cast<std::size_t>(*index)];
    if (!info.derived_from.empty()) {
      entry.at("path").fail("'" + parameter.path + "' is derived (" + info.derived_from +
                            "); fit what it is derived from");
    }
    for (const auto& earlier : parameters) {
      if (earlier.path == parameter.path)
        entry.at("path").fail("'" + parameter.path + "' is listed twice");
    }
    parameter.unit = info.declaration.unit;
    std::tie(parameter.lower, parameter.upper) = entry.interval("bounds", parameter.unit);
    const double value = context.parameter(parameter.path);
    if (value < parameter.lower || value > parameter.upper) {
      entry.at("bounds").fail("the model's value " + number_text(value, 10) + " " + parameter.unit +
                              " is outside the bounds");
    }
    for (const double bound : {parameter.lower, parameter.upper}) {
      const std::string problem = parameter_problem(info.declaration, bound);
      if (!problem.empty()) entry.at("bounds").fail("a bound the model refuses: " + problem);
    }
    parameters.push_back(parameter);
  }
  return parameters;
}

void read_multistart(const ConfigNode& root, FitSettings& settings) {
  const auto multistart = root.find("multistart");
  if (!multistart) return;
  multistart->declare({"starts", "refine", "seed"});
  settings.starts = static_cast<int>(
      multistart->integer_or("starts", settings.starts, ValueCheck::between(0, 10000)));
  settings.refine = static_cast<int>(
      multistart->integer_or("refine", settings.refine, ValueCheck::between(1, 10000)));
  settings.seed =
      static_cast<std::uint64_t>(multistart->integer_or("seed", 1, ValueCheck::non_negative()));
}

// `gradient: automatic | sensitivities | differences`; sensitivities only where the model
// allows them.
Gradient read_gradient(const ConfigNode& root, const FitProblem& problem) {
  const std::string gradient =
      root.choice_or("gradient", {"automatic", "sensitivities", "differences"}, "automatic");
  if (gradient == "differences") return Gradient::differences;
  if (gradient == "automatic") return Gradient::automatic;
  if (const std::string unavailable = sensitivities_unavailable(problem); !unavailable.empty())
    root.at("gradient")
        .fail("forward sensitivities are not available for this model: " + unavailable +
              " (use automatic or differences)");
  return Gradient::sensitivities;
}

}  // namespace

// The model must record at least as often as the data are sampled, from before the windows:
// its outputs are compared at the data's sample times (interpolated between its own).
std::string output_rate_problem(const Scenario& model, const MeasuredData& data, double from,
                                std::string_view set_before, std::string_view set_after) {
  const auto& time = data.time();
  std::vector<double> intervals;
  for (std::size_t k = 1; k < time.size(); ++k) intervals.push_back(time[k] - time[k - 1]);
  if (intervals.empty()) return "the data hold a single sample; a fit needs a time series";
  std::nth_element(intervals.begin(), intervals.begin() + static_cast<long>(intervals.size() / 2),
                   intervals.end());
  const double sampled = intervals[intervals.size() / 2];
  if (model.settings.output_interval > sampled * (1 + 1e-9)) {
    return "the model records at " + number_text(1 / model.settings.output_interval, 6) +
           " Hz, less often than the data are sampled (" + number_text(1 / sampled, 6) +
           " Hz); set its output.rate to at least that (" + std::string(set_before) +
           "output.rate=" + number_text(1 / sampled, 6) + " Hz" + std::string(set_after) + ")";
  }
  if (model.settings.output_start > from) {
    return "the model records from output.start " + number_text(model.settings.output_start, 6) +
           " s, after the identification window starts";
  }
  return "";
}

FitSpec load_fit(const std::string& file, const std::vector<std::string>& overrides,
                 const std::string& data_override, int threads,
                 std::shared_ptr<const UnitSystem> units) {
  const ConfigNode root = ConfigNode::load_file(file, overrides, units);
  root.declare({"model", "set", "data", "outputs", "parameters", "identification", "validation",
                "multistart", "gradient"});
  FitSpec spec;
  spec.file = file;
  spec.model_file = existing_file(root, "model", "scenario");
  if (!data_override.empty()) {
    spec.data_file = data_override;
  } else if (root.has("data")) {
    spec.data_file = existing_file(root, "data", "measurement");
  } else {
    root.fail("expected the measurement: a 'data' file here, or --data on the command line");
  }
  auto data = std::make_shared<const MeasuredData>(read_measured_data(spec.data_file, *units));
  TimeWindow identification = read_window(root, "identification", *data);
  TimeWindow validation = root.has("validation") ? read_window(root, "validation", *data)
                                                 : TimeWindow{identification.to, identification.to};
  if (root.has("validation") && validation.from < identification.to &&
      identification.from < validation.to) {
    root.at("validation")
        .fail("the validation window overlaps the identification window [" +
              seconds_text(identification.from) + ", " + seconds_text(identification.to) +
              "]; data the fit has seen cannot validate it");
  }
  const double end = std::max(identification.to, validation.to);
  std::vector<std::string> model_overrides = sweep::read_set(root);
  model_overrides.push_back("measurement.file=" +
                            single_quoted(std::filesystem::absolute(spec.data_file).string()));
  model_overrides.push_back("scenario.duration=" + number_text(end, 17) + " s");
  std::shared_ptr<const Scenario> model;
  try {
    model =
        std::make_shared<const Scenario>(load_scenario(spec.model_file, model_overrides, units));
  } catch (const ConfigError& error) {
    sweep::blame_set(root, "model", error);
    if (!error.location().origin.empty()) {  // a value the fit sets, not one the user gave
      root.at("model").fail("'" + spec.model_file +
                            "' is no scenario the fit can run with its measurement.file and "
                            "scenario.duration set: " +
                            (error.key_path().empty() ? "" : error.key_path() + ": ") +
                            error.problem());
    }
    throw;
  }
  if (const std::string problem =
          output_rate_problem(*model, *data, identification.from, "set: [", "]");
      !problem.empty()) {
    root.at(problem.find("single sample") != std::string::npos ? "data" : "model").fail(problem);
  }
  spec.problem.model = model;
  spec.problem.data = data;
  spec.problem.identification = identification;
  spec.problem.validation = validation;
  spec.problem.outputs = read_outputs(root, *model, *data);
  spec.problem.parameters = read_parameters(root, *model);
  // Fewer samples than parameters + 1 fit them exactly and leave no residual to estimate errors.
  const std::size_t fitted = spec.problem.parameters.size();
  require_samples(root, "identification", identification, *data, fitted + 1,
                  "a fit of " + std::to_string(fitted) + " parameter" + (fitted == 1 ? "" : "s"));
  if (root.has("validation"))
    require_samples(root, "validation", validation, *data, 1, "scoring it");
  spec.settings.threads = threads;
  read_multistart(root, spec.settings);
  spec.settings.max_iterations = static_cast<int>(root.integer_or(
      "max_iterations", spec.settings.max_iterations, ValueCheck::between(1, 100000)));
  spec.settings.gradient = read_gradient(root, spec.problem);
  root.reject_unknown_keys();
  return spec;
}

}  // namespace tcpmsim::fit
