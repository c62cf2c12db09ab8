#include "identification/discovery_setup.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>

#include "identification/effect_catalogue.h"
#include "identification/measured_roles.h"
#include "identification/noise_floor.h"
#include "kinds/standard_kinds.h"
#include "sim/config/config_error.h"
#include "sim/value_check.h"

namespace tcpmsim::fit {

namespace {

std::string joined(const std::vector<std::string>& names) {
  std::string text;
  for (const auto& name : names) text += (text.empty() ? "" : ", ") + name;
  return text.empty() ? "none" : text;
}

void check_inputs(const DiscoverRequest& request, const Scenario& model, const MeasuredData& data) {
  if (request.inputs.empty()) throw UsageError("--inputs: name at least one channel");
  const auto replayed = replayed_channels(model.resolved_yaml);
  for (const auto& input : request.inputs) {
    if (!data.find(input)) throw UsageError("--inputs: " + data.missing_channel(input));
    if (std::find(replayed.begin(), replayed.end(), input) == replayed.end()) {
      throw UsageError("--inputs: the model " + request.model_file + " replays no channel '" +
                       input + "' (its data signals replay: " + joined(replayed) +
                       "); give it a signal {type: data, channel: " + input + "}");
    }
  }
}

// "force" or "force=load.force": the model output compared with a measured channel. Without
// one named, the bench's instrument for it: the drive's, else the load's, else the muscle's.
std::vector<FitOutput> read_outputs(const DiscoverRequest& request, const Scenario& model,
                                    const MeasuredData& data, const UnitSystem& units) {
  if (request.outputs.empty()) throw UsageError("--outputs: name at least one channel");
  std::vector<FitOutput> outputs;
  const System& system = *model.system;
  const std::string muscle = only_muscle(system);
  for (const auto& entry : request.outputs) {
    FitOutput output;
    const auto equals = entry.find('=');
    output.channel = entry.substr(0, equals);
    const MeasuredChannel* channel = data.find(output.channel);
    if (!channel) throw UsageError("--outputs: " + data.missing_channel(output.channel));
    if (equals != std::string::npos) {
      output.output = entry.substr(equals + 1);
      if (system.signal_index(output.output) < 0)
        throw UsageError("--outputs: the model has no output '" + output.output +
                         "' (outputs are named group.name, as in its record)");
    } else {
      for (const std::string& instrument : std::vector<std::string>{"drive", "load", muscle}) {
        if (system.signal_index(instrument + "." + output.channel) >= 0) {
          output.output = instrument + "." + output.channel;
          break;
        }
      }
      if (output.output.empty())
        throw UsageError("--outputs: the model publishes no '" + output.channel +
                         "' of its drive, load or muscle; name the output, as " + output.channel +
                         "=group.name");
    }
    output.unit =
        system.channels()[static_cast<std::size_t>(system.signal_index(output.output))].unit;
    if (!units.convertible(channel->unit, output.unit) ||
        units.convert(1.0, channel->unit, output.unit) != 1.0)
      throw UsageError("--outputs: channel '" + output.channel + "' is in " + channel->unit +
                       " and output '" + output.output + "' in " + output.unit);
    for (const auto& earlier : outputs) {
      if (earlier.channel == output.channel)
        throw UsageError("--outputs: '" + output.channel + "' is named twice");
    }
    outputs.push_back(output);
  }
  return outputs;
}

// The base model's identifiable parameters, relative to its muscle: the thermal force law's
// (reduced form: kappa_P, kappa_c of (7.1); physical: hA and phi_T), the SLS's (7.5)-(7.6) when
// a force is compared, the coil law's (7.3) when its output is.
std::vector<std::string> default_parameters(const System& system,
                                            const std::vector<FitOutput>& outputs) {
  const std::string m = only_muscle(system) + ".";
  bool coil = false, other = false;
  for (const auto& output : outputs) {
    const bool is_coil = output.output.find("inductance") != std::string::npos;
    coil = coil || is_coil;
    other = other || !is_coil;
  }
  std::vector<std::string> relative;
  if (other) {
    if (system.parameter_index(m + "thermal_force.kappa_P"))
      relative = {"thermal_force.kappa_P", "thermal_force.kappa_c"};
    else
      relative = {"thermal.conductance", "thermal_force.force_per_kelvin"};
    for (const char* key :
         {"mechanics.k1", "mechanics.k2", "mechanics.damping", "mechanics.force_offset"})
      relative.emplace_back(key);
  }
  if (coil) {
    for (const char* key : {"inductance.lambda_0", "inductance.lambda_x", "inductance.lambda_l"})
      relative.emplace_back(key);
  }
  std::vector<std::string> paths;
  for (const auto& key : relative) {
    if (system.parameter_index(m + key)) paths.push_back(m + key);
  }
  return paths;
}

// Bounds a factor of five either side of the model's value.
std::vector<FitParameter> read_parameters(const DiscoverRequest& request, const Scenario& model,
                                          const std::vector<FitOutput>& outputs) {
  const std::vector<std::string> paths =
      request.parameters.empty() ? default_parameters(*model.system, outputs) : request.parameters;
  if (paths.empty())
    throw UsageError(
        "--parameters: the model has none of the default parameters; "
        "name those to fit");
  const Context context = model.make_context();
  std::vector<FitParameter> parameters;
  for (const auto& path : paths) {
    const auto index = model.system->parameter_index(path);
    if (!index) throw UsageError("--parameters: the model has no parameter '" + path + "'");
    const auto& info = model.system->parameters()[static_cast<std::size_t>(*index)];
    if (!info.derived_from.empty())
      throw UsageError("--parameters: '" + path + "' is derived (" + info.derived_from +
                       "); fit what it is derived from");
    const double value = context.parameter(path);
    if (value == 0.0 && request.parameters.empty())
      throw UsageError("--parameters: '" + path +
                       "', one of the parameters discover fits by default (each within a factor "
                       "of five of the model's value), is 0 in the model; give it a starting "
                       "value (--set " +
                       path + "=VALUE UNIT) or name the parameters to fit (--parameters)");
    if (value == 0.0)
      throw UsageError("--parameters: '" + path +
                       "' is 0 in the model; give it a starting value (--set)");
    FitParameter parameter{path, info.declaration.unit, std::min(value / 5, value * 5),
                           std::max(value / 5, value * 5)};
    for (const double bound : {parameter.lower, parameter.upper}) {
      if (const std::string problem = parameter_problem(info.declaration, bound); !problem.empty())
        throw UsageError("--parameters: '" + path +
                         "' at a fifth or five times its value: " + problem);
    }
    parameters.push_back(parameter);
  }
  return parameters;
}

// The identification window ends at the last sample before `from`, validation starts at it.
std::pair<TimeWindow, TimeWindow> windows(const MeasuredData& data, double from) {
  const auto& time = data.time();
  const auto split = std::lower_bound(time.begin(), time.end(), from);
  const auto before = split - time.begin(), after = time.end() - split;
  if (before < 16 || after < 16)
    throw UsageError("--validate-from " + seconds_text(from) +
                     ": both windows need 16 samples or more; the data run from " +
                     seconds_text(time.front()) + " to " + seconds_text(time.back()));
  return {{time.front(), *(split - 1)}, {*split, time.back()}};
}

double median(std::vector<double> values) {
  const auto middle = values.begin() + static_cast<long>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

// The noise floor of each output: given by --noise ("force=2 mN"), else estimated from the
// measurement (both windows, spikes replaced).
void read_floors(const DiscoverRequest& request, const UnitSystem& units, DiscoverSetup& setup) {
  const auto& outputs = setup.base.problem.outputs;
  setup.floor.assign(outputs.size(), 0.0);
  setup.floor_given.assign(outputs.size(), false);
  for (const auto& entry : request.noise) {
    const auto equals = entry.find('=');
    const std::string channel = entry.substr(0, std::min(equals, entry.size()));
    const auto output = std::find_if(outputs.begin(), outputs.end(),
                                     [&](const FitOutput& o) { return o.channel == channel; });
    if (equals == std::string::npos || output == outputs.end())
      throw UsageError("--noise " + entry +
                       ": expected OUTPUT=VALUE UNIT for a compared output, e.g. force=2 mN");
    const std::string text = entry.substr(equals + 1);
    char* end = nullptr;
    const double value = std::strtod(text.c_str(), &end);
    std::string unit(end);
    unit.erase(0, unit.find_first_not_of(' '));
    if (unit.empty()) unit = output->unit;
    if (end == text.c_str() || !std::isfinite(value) || !(value > 0.0) ||
        !units.convertible(unit, output->unit))
      throw UsageError("--noise " + entry + ": expected a positive " + output->unit +
                       " quantity for " + channel +
                       " (in its unit or one convertible to it), e.g. force=2 mN");
    const auto k = static_cast<std::size_t>(output - outputs.begin());
    setup.floor[k] = units.convert_difference(value, unit, output->unit);  // 0.5 degC: 0.5 K
    setup.floor_given[k] = true;
  }
  const FitProblem& problem = setup.base.problem;
  const TimeWindow whole{problem.identification.from, problem.validation.to};
  const auto measured = measured_outputs(problem, whole);
  const auto [first, last] = samples_in(*problem.data, whole);
  std::vector<std::vector<double>> inputs;
  for (const auto& name : request.inputs) {
    const auto& values = problem.data->find(name)->values;
    inputs.emplace_back(values.begin() + static_cast<long>(first),
                        values.begin() + static_cast<long>(last));
  }
  std::vector<const std::vector<double>*> replayed;
  for (const auto& input : inputs) replayed.push_back(&input);
  const auto steps = steps_in_inputs(replayed, last - first);
  for (std::size_t k = 0; k < outputs.size(); ++k) {
    if (setup.floor_given[k]) continue;
    setup.floor[k] = difference_noise_floor(measured[k], steps);
    if (!(setup.floor[k] > 0.0))
      throw UsageError("--noise: the measured " + outputs[k].channel +
                       " holds no noise to estimate a floor from (constant or too short); give "
                       "it, e.g. --noise " +
                       outputs[k].channel + "=VALUE UNIT");
  }
}

}  // namespace

namespace {

// The samples of `values` that stand more than 5 noise standard deviations (robustly, from the
// second differences) and more than `least` off both the median of the three samples before and
// of the three after, on the same side; with the mean of those medians.
std::vector<std::pair<std::size_t, double>> spikes_in(const std::vector<double>& values,
                                                      double least = 0.0) {
  std::vector<std::pair<std::size_t, double>> found;
  const std::size_t n = values.size();
  if (n < 7) return found;
  std::vector<double> second;
  for (std::size_t i = 1; i + 1 < n; ++i)
    second.push_back(std::abs(values[i + 1] - 2 * values[i] + values[i - 1]));
  // White noise's second differences have 6 times its variance; a smooth signal's are far
  // smaller. A noise-free series (a replayed input) counts any excursion.
  const double sigma = 1.4826 * median(second) / std::sqrt(6.0);
  for (std::size_t i = 3; i + 3 < n; ++i) {
    const double before = median({values[i - 3], values[i - 2], values[i - 1]});
    const double after = median({values[i + 1], values[i + 2], values[i + 3]});
    const double from_before = values[i] - before, from_after = values[i] - after;
    if (from_before * from_after > 0 &&
        std::min(std::abs(from_before), std::abs(from_after)) > std::max(5 * sigma, least))
      found.emplace_back(i, 0.5 * (before + after));
  }
  return found;
}

}  // namespace

MeasuredData without_spikes(const MeasuredData& data, const std::vector<std::string>& channels,
                            const std::vector<std::string>& inputs,
                            std::vector<std::size_t>& replaced) {
  // An input's own one-sample excursion drives a true one in the outputs: those stay. It must
  // also pass the input's jump threshold: a noise-free input's noise scale is 0, and every
  // smooth peak of a multisine would count.
  std::vector<char> driven(data.time().size(), 0);
  for (const auto& input : inputs) {
    if (const MeasuredChannel* channel = data.find(input)) {
      for (const auto& [i, level] :
           spikes_in(channel->values, input_jump_threshold(channel->values))) {
        (void)level;
        for (std::size_t j = i - 1; j <= i + 1; ++j) driven[j] = 1;
      }
    }
  }
  std::vector<MeasuredChannel> cleaned = data.channels();
  replaced.assign(channels.size(), 0);
  for (std::size_t c = 0; c < channels.size(); ++c) {
    auto found = std::find_if(cleaned.begin(), cleaned.end(),
                              [&](const auto& channel) { return channel.name == channels[c]; });
    if (found == cleaned.end()) continue;
    for (const auto& [i, level] : spikes_in(found->values)) {
      if (driven[i]) continue;
      found->values[i] = level;
      ++replaced[c];
    }
  }
  return MeasuredData(data.file(), data.time(), std::move(cleaned));
}

std::vector<double> initial_noise(const FitProblem& problem) {
  const Context context = problem.model->make_context();
  std::vector<double> values;
  for (const auto& parameter : problem.parameters)
    values.push_back(context.parameter(parameter.path));
  const auto simulated = simulate_outputs(problem, values, problem.identification);
  const auto measured = measured_outputs(problem, problem.identification);
  std::vector<double> noise;
  for (std::size_t k = 0; k < measured.size(); ++k) {
    double sum = 0.0;
    for (std::size_t i = 0; i < measured[k].size(); ++i)
      sum += std::pow(simulated[k][i] - measured[k][i], 2);
    const double rms =
        std::sqrt(sum / static_cast<double>(std::max<std::size_t>(1, measured[k].size())));
    noise.push_back(rms > 0 && std::isfinite(rms) ? rms : 1.0);
  }
  return noise;
}

DiscoverSetup setup_discovery(const DiscoverRequest& request,
                              std::shared_ptr<const UnitSystem> units) {
  for (const auto& effect : request.effects) {
    const auto& names = effect_names();
    if (std::find(names.begin(), names.end(), effect) == names.end())
      throw UsageError("--effects: no effect '" + effect + "'; the catalogue: " + joined(names));
  }
  DiscoverSetup setup;
  setup.request = request;
  setup.units = units;
  const MeasuredData raw = read_measured_data(request.data_file, *units);
  const auto [identification, validation] = windows(raw, request.validate_from);
  setup.overrides = request.overrides;
  setup.overrides.push_back("measurement.file='" +
                            std::filesystem::absolute(request.data_file).string() + "'");
  setup.overrides.push_back("scenario.duration=" + number_text(validation.to, 17) + " s");
  auto model =
      std::make_shared<const Scenario>(load_scenario(request.model_file, setup.overrides, units));
  check_inputs(request, *model, raw);
  if (const std::string problem =
          output_rate_problem(*model, raw, identification.from, "--set ", "");
      !problem.empty())
    throw UsageError("--model: " + problem);

  FitSpec& spec = setup.base;
  spec.file.clear();
  spec.model_file = request.model_file;
  spec.data_file = request.data_file;
  spec.problem.model = model;
  spec.problem.identification = identification;
  spec.problem.validation = validation;
  spec.problem.outputs = read_outputs(request, *model, raw, *units);
  // The coil's measure spikes (the Muscle Drive's L*, 7.3.6); the load cell does not.
  std::vector<std::string> spiky;
  for (const auto& output : spec.problem.outputs) {
    const bool coil = output.channel.find("inductance") != std::string::npos ||
                      output.channel.find("decay_time") != std::string::npos;
    spiky.push_back(coil || request.despike_all ? output.channel : std::string());
  }
  spec.problem.data = std::make_shared<const MeasuredData>(
      without_spikes(raw, spiky, request.inputs, setup.cleaned));
  spec.problem.parameters = read_parameters(request, *model, spec.problem.outputs);
  setup.roles = measured_roles(*model, *spec.problem.data, spec.problem.outputs);
  spec.settings.starts = request.starts;
  spec.settings.refine = 2;
  spec.settings.seed = request.seed;
  spec.settings.threads = request.threads;
  read_floors(request, *units, setup);
  return setup;
}

}  // namespace tcpmsim::fit
