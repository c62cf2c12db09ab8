#include "signals/signal_config.h"

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "signals/constant_signal.h"
#include "signals/control_task_signals.h"
#include "signals/log_sweep_signal.h"
#include "signals/multisine_signal.h"
#include "signals/periodic_signal.h"
#include "signals/piecewise_constant_signal.h"
#include "signals/piecewise_linear_signal.h"
#include "signals/random_steps.h"
#include "signals/sequence_signal.h"
#include "signals/sine_signal.h"

namespace tcpmsim {

namespace {

std::vector<double> quantities(const ConfigNode& node, std::string_view unit) {
  std::vector<double> values;
  for (const auto& element : node.elements()) values.push_back(element.as_quantity(unit));
  return values;
}

std::string per_second(std::string_view unit) {
  if (unit == "1") return "1/s";
  // Built by appending: GCC 12 warns falsely (-Wrestrict, PR 105329) on "(" + s + ")/s".
  std::string rate = "(";
  rate.append(unit);
  rate.append(")/s");
  return rate;
}

std::unique_ptr<Signal> read_steps(const ConfigNode& node, std::string_view unit) {
  const double initial = node.quantity("initial", unit);
  const auto times_node = node.at("times");
  const auto times = quantities(times_node, "s");
  const auto values_node = node.at("values");
  const auto values = quantities(values_node, unit);
  if (times.size() != values.size()) {
    values_node.fail("expected as many values as times (" + std::to_string(times.size()) +
                     "), got " + std::to_string(values.size()));
  }
  for (std::size_t k = 1; k < times.size(); ++k) {
    if (!(times[k] > times[k - 1])) times_node.fail("step times must increase strictly");
  }
  return std::make_unique<PiecewiseConstantSignal>(initial, times, values);
}

std::unique_ptr<Signal> read_ramp(const ConfigNode& node, std::string_view unit) {
  const double start = node.quantity("start_time", "s", ValueCheck::non_negative());
  const double end = node.quantity("end_time", "s");
  if (!(end > start)) node.at("end_time").fail("expected end_time after start_time");
  return std::make_unique<PiecewiseLinearSignal>(
      std::vector<double>{start, end},
      std::vector<double>{node.quantity("from", unit), node.quantity("to", unit)}, "ramp");
}

std::unique_ptr<Signal> read_piecewise_linear(const ConfigNode& node, std::string_view unit) {
  const auto times_node = node.at("times");
  const auto times = quantities(times_node, "s");
  const auto values_node = node.at("values");
  const auto values = quantities(values_node, unit);
  if (times.empty() || times.size() != values.size()) {
    values_node.fail("expected as many values as times, and at least one");
  }
  for (std::size_t k = 1; k < times.size(); ++k) {
    if (!(times[k] > times[k - 1])) times_node.fail("times must increase strictly");
  }
  return std::make_unique<PiecewiseLinearSignal>(times, values);
}

// Hold each level for `hold`, moving between levels at `rate`: a testing machine's step
// sequence (thesis Fig. 6.3).
std::unique_ptr<Signal> read_staircase(const ConfigNode& node, std::string_view unit) {
  const auto levels_node = node.at("levels");
  const auto levels = quantities(levels_node, unit);
  if (levels.empty()) levels_node.fail("expected at least one level");
  const double hold = node.quantity("hold", "s", ValueCheck::positive());
  const double rate = node.quantity("rate", per_second(unit), ValueCheck::positive());
  double time = node.quantity_or("start_time", "s", 0.0, ValueCheck::non_negative());
  std::vector<double> times{time}, values{levels.front()};
  for (std::size_t k = 1; k < levels.size(); ++k) {
    time += hold;
    times.push_back(time), values.push_back(levels[k - 1]);
    time += std::abs(levels[k] - levels[k - 1]) / rate;
    times.push_back(time), values.push_back(levels[k]);
  }
  return std::make_unique<PiecewiseLinearSignal>(times, values, "staircase");
}

double read_phase(const ConfigNode& node, std::string_view key, RandomStream& stream,
                  bool random_by_default) {
  if (auto phase = node.find(key)) {
    if (phase->is_scalar() && phase->as_text() == "random")
      return stream.uniform(0.0, 2.0 * std::numbers::pi);
    return phase->as_quantity("rad");
  }
  return random_by_default ? stream.uniform(0.0, 2.0 * std::numbers::pi) : 0.0;
}

std::unique_ptr<Signal> read_multisine(const ConfigNode& node, std::string_view unit,
                                       const SignalContext& context) {
  const auto components = static_cast<int>(node.integer("components", ValueCheck::at_least(1)));
  const auto [f_low, f_high] = node.interval("band", "Hz", ValueCheck::positive());
  RandomStream stream(context.seed, node.path());
  const double phase_offset = read_phase(node, "phase_offset", stream, true);
  const MultisineSignal unit_signal =
      MultisineSignal::schroeder(components, f_low, f_high, phase_offset);
  if (node.has("range")) {
    const auto [low, high] = node.interval("range", unit);
    const double duration =
        node.quantity_or("duration", "s", context.duration, ValueCheck::positive());
    return std::make_unique<MultisineSignal>(unit_signal.scaled_to(low, high, duration));
  }
  return std::make_unique<MultisineSignal>(unit_signal.with_equal_amplitudes(
      node.quantity("offset", unit), node.quantity("amplitude", unit)));
}

std::unique_ptr<Signal> read_random_steps(const ConfigNode& node, std::string_view unit,
                                          const SignalContext& context) {
  RandomStepsSettings settings;
  std::tie(settings.low, settings.high) = node.interval("range", unit);
  settings.process_time_constant =
      node.quantity("process_time_constant", "s", ValueCheck::positive());
  settings.sample_rate = node.quantity("sample_rate", "Hz", ValueCheck::positive());
  settings.max_step_fraction = node.number_or("max_step_fraction", 0.25, ValueCheck::fraction());
  settings.scale_to_range = node.boolean_or("scale_to_range", true);
  settings.duration = node.quantity_or("duration", "s", context.duration, ValueCheck::positive());
  if (switching_probability(settings) > 1.0) {
    node.at("process_time_constant")
        .fail("the switching probability 1/(0.5 tau_p f_s) exceeds 1; need tau_p >= 2/f_s = " +
              std::to_string(2.0 / settings.sample_rate) + " s");
  }
  RandomStream stream(context.seed, node.path());
  return make_random_steps(settings, stream);
}

std::unique_ptr<Signal> read_sine(const ConfigNode& node, std::string_view unit,
                                  const SignalContext& context) {
  RandomStream stream(context.seed, node.path());
  return std::make_unique<SineSignal>(node.quantity("offset", unit),
                                      node.quantity("amplitude", unit),
                                      node.quantity("frequency", "Hz", ValueCheck::positive()),
                                      read_phase(node, "phase", stream, false));
}

std::unique_ptr<Signal> read_log_sweep(const ConfigNode& node, std::string_view unit,
                                       const SignalContext& context) {
  const auto [f_start, f_end] = node.interval("band", "Hz", ValueCheck::positive());
  return std::make_unique<LogSweepSignal>(
      node.quantity("offset", unit), node.quantity("amplitude", unit), f_start, f_end,
      node.quantity_or("duration", "s", context.duration, ValueCheck::positive()));
}

std::unique_ptr<Signal> read_sequence(const ConfigNode& node, std::string_view unit,
                                      const SignalContext& context) {
  const auto segments_node = node.at("segments");
  const auto segments = segments_node.elements();
  if (segments.empty()) segments_node.fail("expected at least one segment");
  std::vector<SequenceSignal::Segment> built;
  double start = 0.0;
  for (std::size_t k = 0; k < segments.size(); ++k) {
    const bool last = k + 1 == segments.size();
    const double duration =
        last ? segments[k].quantity_or("duration", "s", std::max(context.duration - start, 0.0),
                                       ValueCheck::non_negative())
             : segments[k].quantity("duration", "s", ValueCheck::positive());
    SignalContext inner = context;
    inner.duration = duration;
    built.push_back({start, read_signal(segments[k].at("signal"), unit, inner)});
    start += duration;
  }
  return std::make_unique<SequenceSignal>(std::move(built));
}

std::unique_ptr<Signal> read_periodic(const ConfigNode& node, std::string_view unit,
                                      const SignalContext& context) {
  const double period = node.quantity("period", "s", ValueCheck::positive());
  SignalContext inner = context;
  inner.duration = period;
  return std::make_unique<PeriodicSignal>(period, read_signal(node.at("signal"), unit, inner));
}

// The thesis' control-task references (7.3.4): a stepped sine sweep (15 log-spaced frequencies
// in [10^-2.4, 10^-1.1] Hz, 3 periods each) and a step sequence (7 levels held 20 s).
std::unique_ptr<Signal> read_stepped_sine_sweep(const ConfigNode& node, std::string_view unit) {
  node.declare({"type", "offset", "amplitude", "band", "frequencies", "periods", "start_time"});
  SineSweepSettings settings;
  settings.offset = node.quantity("offset", unit);
  settings.amplitude = node.quantity("amplitude", unit);
  if (node.has("band")) {
    std::tie(settings.lowest_frequency, settings.highest_frequency) =
        node.interval("band", "Hz", ValueCheck::positive());
  }
  settings.frequencies = static_cast<int>(
      node.integer_or("frequencies", settings.frequencies, ValueCheck::at_least(1)));
  settings.periods = node.number_or("periods", settings.periods, ValueCheck::positive());
  settings.start_time = node.quantity_or("start_time", "s", 0.0, ValueCheck::non_negative());
  return make_stepped_sine_sweep(settings);
}

std::unique_ptr<Signal> read_step_sequence(const ConfigNode& node, std::string_view unit) {
  node.declare({"type", "range", "steps", "hold", "start_time", "initial"});
  StepSequenceSettings settings;
  std::tie(settings.low, settings.high) = node.interval("range", unit);
  settings.steps =
      static_cast<int>(node.integer_or("steps", settings.steps, ValueCheck::at_least(2)));
  settings.hold = node.quantity_or("hold", "s", settings.hold, ValueCheck::positive());
  settings.start_time = node.quantity_or("start_time", "s", 0.0, ValueCheck::non_negative());
  if (auto initial = node.find("initial")) settings.initial = initial->as_quantity(unit);
  return make_step_sequence(settings);
}

}  // namespace

std::unique_ptr<Signal> read_signal(const ConfigNode& node, std::string_view si_unit,
                                    const SignalContext& context) {
  if (node.is_scalar()) return std::make_unique<ConstantSignal>(node.as_quantity(si_unit));
  if (!node.is_map()) node.fail("expected a quantity or a signal mapping with a 'type'");
  const std::string type =
      node.choice("type", {"constant", "steps", "ramp", "piecewise_linear", "staircase", "sine",
                           "multisine", "random_steps", "log_sweep", "sequence", "periodic",
                           "stepped_sine_sweep", "step_sequence"});
  if (type == "constant") return std::make_unique<ConstantSignal>(node.quantity("value", si_unit));
  if (type == "steps") return read_steps(node, si_unit);
  if (type == "ramp") return read_ramp(node, si_unit);
  if (type == "piecewise_linear") return read_piecewise_linear(node, si_unit);
  if (type == "staircase") return read_staircase(node, si_unit);
  if (type == "sine") return read_sine(node, si_unit, context);
  if (type == "multisine") return read_multisine(node, si_unit, context);
  if (type == "random_steps") return read_random_steps(node, si_unit, context);
  if (type == "log_sweep") return read_log_sweep(node, si_unit, context);
  if (type == "periodic") return read_periodic(node, si_unit, context);
  if (type == "stepped_sine_sweep") return read_stepped_sine_sweep(node, si_unit);
  if (type == "step_sequence") return read_step_sequence(node, si_unit);
  return read_sequence(node, si_unit, context);
}

}  // namespace tcpmsim
