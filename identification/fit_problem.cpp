#include "identification/fit_problem.h"

#include <algorithm>
#include <stdexcept>

#include "sim/forward_sensitivity.h"
#include "sim/run.h"
#include "sim/time_grid.h"

namespace tcpmsim::fit {

namespace {

// `values` (at `times`) at `at`: the sample itself when `at` is an output instant, else the
// straight line between the two around it.
double value_at(const std::vector<double>& times, const std::vector<double>& values, double at) {
  const auto after = std::upper_bound(times.begin(), times.end(), at);
  if (after == times.begin()) return values.front();
  const auto k = static_cast<std::size_t>(after - times.begin()) - 1;
  if (same_instant(times[k], at) || k + 1 == times.size()) return values[k];
  if (same_instant(times[k + 1], at)) return values[k + 1];
  const double fraction = (at - times[k]) / (times[k + 1] - times[k]);
  return values[k] + fraction * (values[k + 1] - values[k]);
}

// The chosen outputs and their sensitivities at a run's output times.
class SensitivityPicker final : public SensitivitySink {
 public:
  SensitivityPicker(const System& system, const std::vector<FitOutput>& outputs,
                    std::size_t parameters)
      : sensitivities(outputs.size(), std::vector<std::vector<double>>(parameters)),
        picker_(system, output_names(outputs)) {
    for (const auto& output : outputs) indices_.push_back(system.signal_index(output.output));
  }
  void record(double time, std::span<const double> signals) override {
    picker_.record(time, signals);
  }
  void record_sensitivities(double, const ForwardSensitivities& tracked) override {
    for (std::size_t k = 0; k < indices_.size(); ++k) {
      for (int j = 0; j < tracked.count(); ++j) {
        sensitivities[k][static_cast<std::size_t>(j)].push_back(
            tracked.output_sensitivity(j)[static_cast<std::size_t>(indices_[k])]);
      }
    }
  }
  const OutputPicker& picker() const { return picker_; }
  std::vector<std::vector<std::vector<double>>> sensitivities;  // by output, by parameter

 private:
  static std::vector<std::string> output_names(const std::vector<FitOutput>& outputs) {
    std::vector<std::string> names;
    for (const auto& output : outputs) names.push_back(output.output);
    return names;
  }
  OutputPicker picker_;
  std::vector<int> indices_;
};

// A run's series (at `times`) at the measurement's samples in [first, last).
std::vector<double> at_samples(const MeasuredData& data, std::size_t first, std::size_t last,
                               const std::vector<double>& times,
                               const std::vector<double>& values) {
  std::vector<double> sampled;
  sampled.reserve(last - first);
  for (std::size_t i = first; i < last; ++i)
    sampled.push_back(value_at(times, values, data.time()[i]));
  return sampled;
}

Context context_at(const FitProblem& problem, const std::vector<double>& values) {
  Context context = problem.model->make_context();
  for (std::size_t j = 0; j < problem.parameters.size(); ++j)
    context.set_parameter(problem.parameters[j].path, values[j]);
  return context;
}

}  // namespace

std::string sensitivities_unavailable(const FitProblem& problem) {
  if (problem.model->solver.method != IntegrationMethod::bdf)
    return "the model is integrated with the Adams method";
  return ForwardSensitivities::unsupported_reason(*problem.model->system);
}

OutputSensitivities simulate_sensitivities(const FitProblem& problem,
                                           const std::vector<double>& values,
                                           const std::vector<std::size_t>& tracked,
                                           const TimeWindow& window) {
  Context context = context_at(problem, values);
  const System& system = *problem.model->system;
  std::vector<int> indices;
  std::vector<double> scales;
  for (std::size_t j : tracked) {
    const auto& parameter = problem.parameters[j];
    indices.push_back(*system.parameter_index(parameter.path));
    // The step follows the value, or the bound range for a value at zero.
    scales.push_back(values[j] != 0.0 ? std::abs(values[j]) : parameter.upper - parameter.lower);
  }
  ForwardSensitivities sensitivities(context, indices, scales);
  SensitivityPicker picker(system, problem.outputs, tracked.size());
  const Scenario& scenario = *problem.model;
  Integrator integrator(system, context, scenario.solver);
  integrator.run(0.0, scenario.settings.duration,
                 {scenario.settings.output_interval, scenario.settings.output_start}, sensitivities,
                 picker);
  const auto [first, last] = samples_in(*problem.data, window);
  const auto& times = picker.picker().times;
  OutputSensitivities result;
  result.sensitivities.resize(problem.outputs.size());
  for (std::size_t k = 0; k < problem.outputs.size(); ++k) {
    result.values.push_back(
        at_samples(*problem.data, first, last, times, picker.picker().values[k]));
    for (const auto& series : picker.sensitivities[k])
      result.sensitivities[k].push_back(at_samples(*problem.data, first, last, times, series));
  }
  return result;
}

const ChannelInfo& named_output(const System& system, const ConfigNode& node,
                                std::string_view owner) {
  const std::string output = node.as_text();
  const int index = system.signal_index(output);
  if (index < 0) {
    node.fail("the " + std::string(owner) + " has no output '" + output +
              "' (outputs are named group.name, as in its record)");
  }
  return system.channels()[static_cast<std::size_t>(index)];
}

OutputPicker::OutputPicker(const System& system, const std::vector<std::string>& outputs) {
  for (const auto& output : outputs) {
    const int index = system.signal_index(output);
    if (index < 0) throw std::invalid_argument("the model has no output " + output);
    indices_.push_back(index);
  }
  values.resize(indices_.size());
}

void OutputPicker::record(double time, std::span<const double> signals) {
  times.push_back(time);
  for (std::size_t k = 0; k < indices_.size(); ++k)
    values[k].push_back(signals[static_cast<std::size_t>(indices_[k])]);
}

std::pair<std::size_t, std::size_t> samples_in(const MeasuredData& data, const TimeWindow& window) {
  const auto& time = data.time();
  const auto first =
      std::lower_bound(time.begin(), time.end(), window.from - time_margin(window.from));
  const auto last = std::upper_bound(time.begin(), time.end(), window.to + time_margin(window.to));
  return {static_cast<std::size_t>(first - time.begin()),
          static_cast<std::size_t>(last - time.begin())};
}

std::string window_samples_problem(const MeasuredData& data, const TimeWindow& window,
                                   std::size_t minimum, std::string_view needed_for) {
  const auto [first, last] = samples_in(data, window);
  const std::size_t held = last - first;
  if (held >= minimum) return "";
  const std::string window_text =
      "the window [" + seconds_text(window.from) + ", " + seconds_text(window.to) + "]";
  const std::string needs = std::string(needed_for) + " needs at least " + std::to_string(minimum);
  if (held == 0)
    return window_text +
           " holds no sample of the data (a gap in their times, or a window between "
           "two samples); " +
           needs;
  return window_text + " holds " + std::to_string(held) + " sample" + (held == 1 ? "" : "s") +
         " of the data; " + needs;
}

std::vector<std::vector<double>> simulate_outputs(const FitProblem& problem,
                                                  const std::vector<double>& values,
                                                  const TimeWindow& window) {
  Context context = context_at(problem, values);
  std::vector<std::string> outputs;
  for (const auto& output : problem.outputs) outputs.push_back(output.output);
  OutputPicker picker(*problem.model->system, outputs);
  integrate(*problem.model, context, picker);
  const auto [first, last] = samples_in(*problem.data, window);
  std::vector<std::vector<double>> sampled;
  for (std::size_t k = 0; k < problem.outputs.size(); ++k)
    sampled.push_back(at_samples(*problem.data, first, last, picker.times, picker.values[k]));
  return sampled;
}

std::vector<std::vector<double>> measured_outputs(const FitProblem& problem,
                                                  const TimeWindow& window) {
  const auto [first, last] = samples_in(*problem.data, window);
  std::vector<std::vector<double>> measured;
  for (const auto& output : problem.outputs) {
    const auto& values = problem.data->find(output.channel)->values;
    measured.emplace_back(values.begin() + static_cast<long>(first),
                          values.begin() + static_cast<long>(last));
  }
  return measured;
}

}  // namespace tcpmsim::fit
