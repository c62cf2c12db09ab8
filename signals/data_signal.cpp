#include "signals/data_signal.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

#include "sim/io/measured_data.h"

namespace tcpmsim {

namespace {

std::vector<double> shifted(const std::vector<double>& times, double origin) {
  std::vector<double> scenario_times(times.size());
  std::transform(times.begin(), times.end(), scenario_times.begin(),
                 [origin](double time) { return time - origin; });
  return scenario_times;
}

// Why samples starting at `first` and covering until `until` (data time) cannot drive
// [origin, origin + duration]; empty if they can.
std::string coverage_problem(const DataSignal& signal, double first, double origin,
                             double duration) {
  if (first > origin) {
    return "the data start at " + seconds_text(first) + ", after origin " + seconds_text(origin) +
           " (the data time of the scenario's t = 0)";
  }
  if (signal.covered_until() < duration) {
    return "the data cover the scenario only until t = " + seconds_text(signal.covered_until()) +
           " (a sample interval past the last sample); the scenario lasts " +
           seconds_text(duration);
  }
  return "";
}

// The samples where a held value changes, or where the slope of the lines through them does
// (constant before the first sample and after the last).
std::vector<double> jumps(const std::vector<double>& times, const std::vector<double>& values,
                          DataInterpolation interpolation) {
  std::vector<double> breakpoints;
  const std::size_t n = times.size();
  if (interpolation == DataInterpolation::hold) {
    for (std::size_t k = 1; k < n; ++k) {
      if (values[k] != values[k - 1]) breakpoints.push_back(times[k]);
    }
    return breakpoints;
  }
  double before = 0.0;  // the slope before sample k
  for (std::size_t k = 0; k < n; ++k) {
    const double after = k + 1 < n ? (values[k + 1] - values[k]) / (times[k + 1] - times[k]) : 0.0;
    if (after != before) breakpoints.push_back(times[k]);
    before = after;
  }
  return breakpoints;
}

}  // namespace

DataSignal::DataSignal(std::shared_ptr<const Samples> samples, DataInterpolation interpolation,
                       double origin)
    : samples_(std::move(samples)),
      times_(shifted(samples_->times, origin)),
      interpolation_(interpolation),
      origin_(origin) {
  if (samples_->times.empty() || samples_->times.size() != samples_->values.size()) {
    throw std::invalid_argument("data signal: need equally many times and values");
  }
  breakpoints_ = jumps(times_, samples_->values, interpolation_);
  if (times_.size() > 1)
    samples_per_second_ = static_cast<double>(times_.size() - 1) / (times_.back() - times_.front());
}

long DataSignal::sample_at(double time) const {
  // The solver asks for a value at every right-hand side, so the binary search over thousands of
  // samples was a tenth of a fit's time. A measurement is sampled at (nearly) one rate: the
  // sample the mean rate puts at `time` is the one, or a neighbour of it.
  const std::size_t n = times_.size();
  if (time >= times_.back()) return static_cast<long>(n) - 1;
  if (time < times_.front()) return -1;
  if (!std::isnan(time)) {
    const double position = (time - times_.front()) * samples_per_second_;
    std::size_t at = std::min(static_cast<std::size_t>(position), n - 2);
    // Here times_[0] <= time < times_[n - 1]: the sample sought has 0 <= at <= n - 2.
    for (int step = 0; step < 4; ++step) {
      if (times_[at] > time) {
        --at;
      } else if (times_[at + 1] <= time) {
        ++at;
      } else {
        return static_cast<long>(at);
      }
    }
  }
  return static_cast<long>(std::upper_bound(times_.begin(), times_.end(), time) - times_.begin()) -
         1;
}

double DataSignal::value(double time) const {
  const auto& values = samples_->values;
  const long k = sample_at(time);
  if (k < 0) return values.front();
  const auto at = static_cast<std::size_t>(k);
  if (interpolation_ == DataInterpolation::hold || at + 1 == values.size()) return values[at];
  const double fraction = (time - times_[at]) / (times_[at + 1] - times_[at]);
  return values[at] + fraction * (values[at + 1] - values[at]);
}

double DataSignal::slope(double time) const {
  const long k = sample_at(time);
  if (interpolation_ == DataInterpolation::hold || k < 0) return 0.0;
  const auto at = static_cast<std::size_t>(k);
  if (at + 1 == times_.size()) return 0.0;
  return (samples_->values[at + 1] - samples_->values[at]) / (times_[at + 1] - times_[at]);
}

double DataSignal::next_breakpoint_after(double time) const {
  const auto after = std::upper_bound(breakpoints_.begin(), breakpoints_.end(), time);
  return after == breakpoints_.end() ? kNoBreakpoint : *after;
}

SignalDescription DataSignal::describe() const {
  const double linear = interpolation_ == DataInterpolation::linear ? 1.0 : 0.0;
  return {"data",
          {{"origin", origin_}, {"linear", linear}},
          {{"times", times_}, {"values", samples_->values}},
          {}};
}

std::pair<double, double> DataSignal::range(double begin, double end) const {
  double low = std::min(value(begin), value(end));
  double high = std::max(value(begin), value(end));
  const auto first = std::upper_bound(times_.begin(), times_.end(), begin);
  const auto last = std::lower_bound(times_.begin(), times_.end(), end);
  for (auto at = first; at < last; ++at) {
    const double sample = samples_->values[static_cast<std::size_t>(at - times_.begin())];
    low = std::min(low, sample);
    high = std::max(high, sample);
  }
  return {low, high};
}

double DataSignal::covered_until() const {
  const std::size_t n = times_.size();
  return n < 2 ? times_.back() : 2.0 * times_[n - 1] - times_[n - 2];
}

std::unique_ptr<Signal> read_data_signal(const ConfigNode& node, std::string_view si_unit,
                                         const SignalContext& context) {
  node.declare({"type", "file", "channel", "interpolation", "origin"});
  // A file of its own, or the scenario's measurement.
  const std::optional<ConfigNode> own_file = node.find("file");
  if (!own_file && context.measurement_file.empty()) {
    node.fail(
        "expected a file to replay: 'file', or the scenario's measurement.file (fit and "
        "discover set it to their --data; run takes --set measurement.file=FILE)");
  }
  const ConfigNode& located = own_file ? *own_file : node;
  const MeasuredData data = read_measured_data(
      own_file ? file_named_by(*own_file) : context.measurement_file, node.units());
  const ConfigNode channel_node = node.at("channel");
  const std::string name = channel_node.as_text();
  if (name == "time") channel_node.fail("time is the data's clock, not a channel to replay");
  const MeasuredChannel* channel = data.find(name);
  if (!channel) channel_node.fail(data.missing_channel(name));
  auto samples = std::make_shared<DataSignal::Samples>();
  samples->times = data.time();
  try {
    const auto to_signal_unit = node.units().converter(channel->unit, si_unit);
    for (double value : channel->values) samples->values.push_back(to_signal_unit(value));
  } catch (const UnitError&) {
    channel_node.fail("channel '" + name + "' is in " + channel->unit + "; this signal takes " +
                      std::string(si_unit));
  }
  const auto interpolation = node.choice_or("interpolation", {"hold", "linear"}, "linear") == "hold"
                                 ? DataInterpolation::hold
                                 : DataInterpolation::linear;
  const double origin = node.quantity_or("origin", "s", 0.0);
  const double first = samples->times.front();
  auto signal = std::make_unique<DataSignal>(samples, interpolation, origin);
  const std::string problem = coverage_problem(*signal, first, origin, context.duration);
  if (!problem.empty()) located.fail(problem);

  auto recipe = std::make_shared<SignalRecipe>();
  recipe->parameters.push_back({node.parameter_path("origin"), "s", origin, {}, {}});
  const double duration = context.duration;
  recipe->make = [samples, interpolation, first, duration](std::span<const double> own,
                                                           std::vector<std::unique_ptr<Signal>>) {
    auto rebuilt = std::make_unique<DataSignal>(samples, interpolation, own[0]);
    const std::string problem = coverage_problem(*rebuilt, first, own[0], duration);
    if (!problem.empty()) throw std::invalid_argument(problem);
    return rebuilt;
  };
  signal->set_recipe(std::move(recipe));
  return signal;
}

}  // namespace tcpmsim
