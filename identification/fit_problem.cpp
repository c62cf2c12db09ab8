#include "identification/fit_problem.h"

#include <algorithm>
#include <stdexcept>

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

}  // namespace

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

std::vector<std::vector<double>> simulate_outputs(const FitProblem& problem,
                                                  const std::vector<double>& values,
                                                  const TimeWindow& window) {
  Context context = problem.model->make_context();
  for (std::size_t j = 0; j < problem.parameters.size(); ++j)
    context.set_parameter(problem.parameters[j].path, values[j]);
  std::vector<std::string> outputs;
  for (const auto& output : problem.outputs) outputs.push_back(output.output);
  OutputPicker picker(*problem.model->system, outputs);
  integrate(*problem.model, context, picker);
  const auto [first, last] = samples_in(*problem.data, window);
  std::vector<std::vector<double>> sampled(problem.outputs.size());
  for (std::size_t k = 0; k < problem.outputs.size(); ++k) {
    for (std::size_t i = first; i < last; ++i)
      sampled[k].push_back(value_at(picker.times, picker.values[k], problem.data->time()[i]));
  }
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
