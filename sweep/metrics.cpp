#include "sweep/metrics.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "analysis/control_tasks.h"
#include "analysis/statistics.h"
#include "analysis/task_runs.h"
#include "signals/control_task_signals.h"
#include "sim/not_a_number.h"

namespace tcpmsim::sweep {
namespace {

// Samples within this of a window's end belong to it (output times carry rounding).
constexpr double kTimeSlack = 1e-9;

struct KindName {
  MetricKind kind;
  const char* name;
};
constexpr KindName kKinds[] = {
    {MetricKind::final_value, "final_value"}, {MetricKind::maximum, "maximum"},
    {MetricKind::minimum, "minimum"},         {MetricKind::mean, "mean"},
    {MetricKind::integral, "integral"},       {MetricKind::rise_time, "rise_time"},
    {MetricKind::overshoot, "overshoot"},     {MetricKind::time_constant, "time_constant"},
    {MetricKind::bandwidth, "bandwidth"},     {MetricKind::rmse, "rmse"},
};

MetricKind kind_named(const std::string& name) {
  for (const auto& entry : kKinds) {
    if (name == entry.name) return entry.kind;
  }
  return MetricKind::final_value;  // unreachable: the name was read as a choice of these
}

// A time for a message: "400", "3756.2".

const ChannelInfo* recorded_channel(const System& system, const std::string& name) {
  for (const auto& channel : system.channels()) {
    if (channel.recorded && channel.group + "/" + channel.name == name) return &channel;
  }
  return nullptr;
}

// A channel key: a recorded output of the scenario, "group/name".
std::string read_channel(const ConfigNode& node, std::string_view key,
                         const std::string& scenario_name, const Scenario& scenario,
                         std::string* unit = nullptr) {
  const ConfigNode value = node.at(key);
  const std::string name = value.as_text();
  const ChannelInfo* channel = recorded_channel(*scenario.system, name);
  if (channel == nullptr) {
    std::vector<std::string> names;
    for (const auto& info : scenario.system->channels())
      if (info.recorded) names.push_back(info.group + "/" + info.name);
    const std::string close = closest_match(name, names);
    value.fail("scenario '" + scenario_name + "' records no output '" + name + "'" +
               (close.empty() ? "" : " (did you mean '" + close + "'?)") +
               "; tcpmsim validate lists its outputs");
  }
  if (unit != nullptr) *unit = channel->unit;
  return name;
}

// The signal a reference channel shows: the prescribed signal of the same group and name.
const Signal* reference_signal(const System& system, const Context& context,
                               const std::string& channel) {
  const auto& slots = system.signal_slots();
  for (std::size_t slot = 0; slot < slots.size(); ++slot) {
    if (slots[slot].group + "/" + slots[slot].name == channel)
      return &context.signal(static_cast<int>(slot));
  }
  return nullptr;
}

// The indices of the samples in [from, to].
std::pair<std::size_t, std::size_t> window(const std::vector<double>& time, double from,
                                           double to) {
  const auto begin = static_cast<std::size_t>(
      std::lower_bound(time.begin(), time.end(), from - kTimeSlack) - time.begin());
  const auto end = static_cast<std::size_t>(
      std::upper_bound(time.begin(), time.end(), to + kTimeSlack) - time.begin());
  return {begin, std::max(begin, end)};
}

// Over the samples of [begin, end): trapezoids, or each value held until the next sample (exact
// for what changes only at samples: a sampled controller's command, a step on the output grid).
double integral_over(const std::vector<double>& time, const std::vector<double>& values,
                     std::size_t begin, std::size_t end, bool held) {
  double sum = 0.0;
  for (std::size_t k = begin + 1; k < end; ++k) {
    const double height = held ? values[k - 1] : 0.5 * (values[k] + values[k - 1]);
    sum += height * (time[k] - time[k - 1]);
  }
  return sum;
}

// The time constant of y = a + b exp(-t / tau) sampled at t_k: the differences d_k = y_k+1 -
// y_k are b (exp(-dt_k / tau) - 1) exp(-t_k / tau), so for equal steps ln|d_k| is linear in t_k
// with slope -1/tau whatever a and b. Fitted by least squares weighted by d_k^2 (the variance
// of ln|d| from an error e in y is e^2 / d^2), so the samples near the end, where the
// differences sink into the solver's error, count for little.
MetricValue time_constant(const std::vector<double>& time, const std::vector<double>& y,
                          std::size_t begin, std::size_t end) {
  if (end < begin + 3) return {kNaN, "fewer than three samples in the window"};
  // The approach's direction from the whole window, not from its first difference (which may be
  // flat or noise).
  const double sign = std::copysign(1.0, y[end - 1] - y[begin]);
  Eigen::MatrixXd design(static_cast<Eigen::Index>(end - begin - 1), 2);
  Eigen::VectorXd target(design.rows());
  Eigen::Index rows = 0;
  for (std::size_t k = begin; k + 1 < end; ++k) {
    const double difference = (y[k + 1] - y[k]) * sign;
    if (!(difference > 0.0)) continue;  // past the approach (or flat): no information
    const double weight = difference;   // sqrt of d^2
    design(rows, 0) = weight;
    design(rows, 1) = weight * time[k];
    target(rows) = weight * std::log(difference);
    ++rows;
  }
  if (rows < 2) return {kNaN, "no exponential approach in the window"};
  const Eigen::Vector2d fit = design.topRows(rows).colPivHouseholderQr().solve(target.head(rows));
  if (!(fit(1) < 0.0)) return {kNaN, "the response does not approach a final value"};
  return {-1.0 / fit(1), ""};
}

// The response's step from `begin` (the step instant) to its value at the window's end, as
// analysis/control_tasks.h measures a step: the reference is the final value.
StepRise open_loop_step(const std::vector<double>& time, const std::vector<double>& y,
                        std::size_t begin, std::size_t end, const RiseTimeDefinition& definition) {
  const std::size_t first = begin > 0 ? begin - 1 : begin;
  std::vector<double> t(time.begin() + static_cast<long>(first),
                        time.begin() + static_cast<long>(end));
  std::vector<double> response(y.begin() + static_cast<long>(first),
                               y.begin() + static_cast<long>(end));
  std::vector<double> reference(response.size(), y[end - 1]);
  if (begin > 0) reference[0] = y[begin];  // the step is the next sample
  auto rises = step_rise_times(t, reference, response, definition);
  return rises.empty() ? StepRise{} : rises.front();
}

MetricValue rise_time(const MetricSpec& metric, const MemoryRecord& record, const Context& context,
                      std::size_t begin, std::size_t end) {
  const auto& y = record[metric.channel];
  if (metric.reference.empty()) {
    const StepRise rise = open_loop_step(record.time, y, begin, end, {metric.lower, metric.upper});
    if (!rise.reached) return {kNaN, "the response never reaches the upper level"};
    return {rise.rise_time, ""};
  }
  TaskAnalysis analysis;
  analyse_task(record, *reference_signal(context.system(), context, metric.reference),
               metric.reference, metric.channel, "", analysis);
  std::vector<double> times;
  for (const auto& rise : analysis.rises) times.push_back(rise.rise_time);
  if (times.empty()) return {kNaN, "the reference has no step"};
  return {analysis::percentile(times, 50.0), ""};
}

// The unit of a metric's value, from its channel's.
std::string value_unit(MetricKind kind, const std::string& channel_unit) {
  switch (kind) {
    case MetricKind::rise_time:
    case MetricKind::time_constant:
      return std::string("s");
    case MetricKind::overshoot:
      return std::string("1");
    case MetricKind::bandwidth:
      return std::string("Hz");
    case MetricKind::integral:
      return channel_unit == "1" ? std::string("s") : channel_unit + "*s";
    default:
      return channel_unit;
  }
}

}  // namespace

const std::vector<std::string>& metric_kind_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> all;
    for (const auto& entry : kKinds) all.emplace_back(entry.name);
    return all;
  }();
  return names;
}

MetricSpec read_metric(const ConfigNode& node, const std::string& scenario_name,
                       const Scenario& scenario) {
  MetricSpec metric;
  metric.scenario = scenario_name;
  metric.name = node.text("name");
  metric.kind = kind_named(node.choice("type", metric_kind_names()));
  std::string unit;
  metric.channel = read_channel(node, "channel", scenario_name, scenario, &unit);
  const double duration = scenario.settings.duration;
  if (metric.kind == MetricKind::bandwidth) {
    for (const char* key : {"from", "to"}) {
      if (node.has(key)) node.at(key).fail("a bandwidth is of the whole sweep: it takes no window");
    }
  }
  metric.from = node.quantity_or("from", "s", 0.0, ValueCheck::non_negative());
  // Without 'to' the window ends with each run (a structural axis may change its duration).
  if (node.has("to")) metric.to = node.quantity("to", "s", ValueCheck::positive());
  if (metric.to <= metric.from) node.at("to").fail("the window must end after it starts ('from')");
  if (metric.from >= duration)
    node.at("from").fail("the window starts after the scenario ends (" + number_text(duration) +
                         " s)");
  if (node.has("to") && metric.to > duration + kTimeSlack)
    node.at("to").fail("the window ends after the scenario does (" + number_text(duration) + " s)");
  if (metric.kind == MetricKind::rise_time) {
    if (node.has("reference"))
      metric.reference = read_channel(node, "reference", scenario_name, scenario);
    else if (metric.from <= 0.0)
      node.fail("an open-loop rise time needs 'from': the step's instant, after the first sample");
    metric.lower = node.number_or("lower", 0.1, ValueCheck::fraction());
    metric.upper = node.number_or("upper", 0.9, ValueCheck::fraction());
    if (metric.upper <= metric.lower) node.at("upper").fail("must exceed 'lower'");
  }
  if (metric.kind == MetricKind::integral)
    metric.held = node.choice_or("rule", {"trapezoidal", "held"}, "trapezoidal") == "held";
  if (metric.kind == MetricKind::bandwidth) {
    metric.reference = read_channel(node, "reference", scenario_name, scenario);
  }
  if (metric.kind == MetricKind::rmse)
    metric.estimate = read_channel(node, "estimate", scenario_name, scenario);
  metric.unit = value_unit(metric.kind, unit);
  if (!metric.reference.empty()) {
    Context context = scenario.make_context();
    const Signal* signal = reference_signal(*scenario.system, context, metric.reference);
    if (signal == nullptr)
      node.at("reference").fail("'" + metric.reference + "' is not a prescribed signal");
    const auto* sweep = dynamic_cast<const SteppedSineSignal*>(signal);
    if (metric.kind == MetricKind::bandwidth && sweep == nullptr)
      node.at("reference").fail("a bandwidth needs a stepped_sine_sweep reference");
    if (metric.kind == MetricKind::bandwidth && sweep->end_time() > duration + kTimeSlack)
      node.at("reference")
          .fail("the sweep ends at " + number_text(sweep->end_time()) +
                " s, after the scenario does (" + number_text(duration) + " s)");
  }
  return metric;
}

MetricValue evaluate_metric(const MetricSpec& metric, const MemoryRecord& record,
                            const Context& context) {
  const auto& time = record.time;
  const auto& y = record[metric.channel];
  const auto [begin, end] = window(time, metric.from, metric.to);
  if (end == begin) return {kNaN, "no sample in the window"};
  const std::span<const double> values(y.data() + begin, end - begin);
  switch (metric.kind) {
    case MetricKind::final_value:
      return {y[end - 1], ""};
    case MetricKind::maximum:
      return {*std::max_element(values.begin(), values.end()), ""};
    case MetricKind::minimum:
      return {*std::min_element(values.begin(), values.end()), ""};
    case MetricKind::mean:
      return {analysis::mean(values), ""};
    case MetricKind::integral:
      return {integral_over(time, y, begin, end, metric.held), ""};
    case MetricKind::time_constant:
      return time_constant(time, y, begin, end);
    case MetricKind::rise_time:
      return rise_time(metric, record, context, begin, end);
    case MetricKind::overshoot: {
      const double start = y[begin], last = y[end - 1];
      if (last == start) return {kNaN, "the response does not move"};
      const double beyond = last > start ? *std::max_element(values.begin(), values.end()) - last
                                         : last - *std::min_element(values.begin(), values.end());
      return {beyond / std::abs(last - start), ""};
    }
    case MetricKind::bandwidth: {
      const Signal* reference = reference_signal(context.system(), context, metric.reference);
      if (reference == nullptr)
        return {kNaN, "'" + metric.reference + "' is not a prescribed signal"};
      TaskAnalysis analysis;
      analyse_task(record, *reference, metric.reference, metric.channel, "", analysis);
      if (!analysis.bandwidth) return {kNaN, "no -3 dB crossing within the sweep"};
      return {*analysis.bandwidth, ""};
    }
    case MetricKind::rmse: {
      const auto& estimate = record[metric.estimate];
      std::vector<double> errors;
      for (std::size_t k = begin; k < end; ++k)
        if (std::isfinite(estimate[k])) errors.push_back(estimate[k] - y[k]);
      if (errors.empty()) return {kNaN, "no estimate in the window"};
      return {analysis::root_mean_square(errors), ""};
    }
  }
  return {};
}

}  // namespace tcpmsim::sweep
