#include "signals/signal_readers.h"

#include <cmath>
#include <numbers>
#include <stdexcept>
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
using Values = std::span<const double>;
using Parts = std::vector<std::unique_ptr<Signal>>;

// The numeric parameters a signal's reader meets, in reading order: each read from the
// scenario and declared under its path at once.
class Declared {
 public:
  double add(const ConfigNode& value_node, double value, std::string_view unit,
             const ValueCheck& check = {}) {
    list.push_back({value_node.parameter_path(), std::string(unit), value, check, {}});
    return value;
  }
  double quantity(const ConfigNode& node, std::string_view key, std::string_view unit,
                  const ValueCheck& check = {}) {
    const ConfigNode value = node.at(key);
    return add(value, value.as_quantity(unit, check), unit, check);
  }
  double quantity_or(const ConfigNode& node, std::string_view key, std::string_view unit,
                     double fallback, const ValueCheck& check = {}) {
    const double value = node.quantity_or(key, unit, fallback, check);
    list.push_back({node.parameter_path(key), std::string(unit), value, check, {}});
    return value;
  }
  std::pair<double, double> interval(const ConfigNode& node, std::string_view key,
                                     std::string_view unit, const ValueCheck& check = {}) {
    const auto bounds = node.interval(key, unit, check);
    const std::string path = node.parameter_path(key);
    list.push_back({path + "[0]", std::string(unit), bounds.first, check, {}});
    list.push_back({path + "[1]", std::string(unit), bounds.second, check, {}});
    return bounds;
  }
  std::vector<double> quantities(const ConfigNode& node, std::string_view unit) {
    std::vector<double> values;
    for (const auto& element : node.elements())
      values.push_back(add(element, element.as_quantity(unit), unit));
    return values;
  }

  std::vector<ParameterDeclaration> list;
};

// Attaches the recipe that rebuilds `signal` from its parameters.
std::unique_ptr<Signal> with_recipe(std::unique_ptr<Signal> signal, Declared declared,
                                    SignalRecipe::Make make,
                                    std::vector<std::shared_ptr<const SignalRecipe>> parts = {}) {
  auto recipe = std::make_shared<SignalRecipe>();
  recipe->parameters = std::move(declared.list);
  recipe->parts = std::move(parts);
  recipe->make = std::move(make);
  signal->set_recipe(std::move(recipe));
  return signal;
}

std::vector<double> slice(Values values, std::size_t first, std::size_t count) {
  return {values.begin() + static_cast<long>(first),
          values.begin() + static_cast<long>(first + count)};
}

void require_increasing(const std::vector<double>& times, const char* problem) {
  for (std::size_t k = 1; k < times.size(); ++k) {
    if (!(times[k] > times[k - 1])) throw std::invalid_argument(problem);
  }
}

std::string per_second(std::string_view unit) {
  if (unit == "1") return "1/s";
  // Built by appending: GCC 12 warns falsely (-Wrestrict, PR 105329) on "(" + s + ")/s".
  std::string rate = "(";
  rate.append(unit);
  rate.append(")/s");
  return rate;
}

std::unique_ptr<Signal> constant_at(const ConfigNode& value_node, std::string_view unit) {
  Declared declared;
  const double value = declared.add(value_node, value_node.as_quantity(unit), unit);
  return with_recipe(std::make_unique<ConstantSignal>(value), std::move(declared),
                     [](Values v, Parts) { return std::make_unique<ConstantSignal>(v[0]); });
}

std::unique_ptr<Signal> make_ramp(double start, double end, double from, double to) {
  if (!(end > start)) throw std::invalid_argument("expected end_time after start_time");
  return std::make_unique<PiecewiseLinearSignal>(std::vector<double>{start, end},
                                                 std::vector<double>{from, to}, "ramp");
}

// Hold each level for `hold`, moving between levels at `rate`: a testing machine's step
// sequence (thesis Fig. 6.3).
std::unique_ptr<Signal> make_staircase(const std::vector<double>& levels, double hold, double rate,
                                       double start_time) {
  double time = start_time;
  std::vector<double> times{time}, values{levels.front()};
  for (std::size_t k = 1; k < levels.size(); ++k) {
    time += hold;
    times.push_back(time), values.push_back(levels[k - 1]);
    time += std::abs(levels[k] - levels[k - 1]) / rate;
    times.push_back(time), values.push_back(levels[k]);
  }
  return std::make_unique<PiecewiseLinearSignal>(times, values, "staircase");
}

// A phase: a quantity in rad (a parameter), `random` (drawn once from the signal's stream), or
// absent (random or 0).
double read_phase(const ConfigNode& node, std::string_view key, RandomStream& stream,
                  bool random_by_default, Declared& declared) {
  if (auto phase = node.find(key)) {
    if (phase->is_word("random")) return stream.uniform(0.0, 2.0 * std::numbers::pi);
    return declared.add(*phase, phase->as_quantity("rad"), "rad");
  }
  return random_by_default ? stream.uniform(0.0, 2.0 * std::numbers::pi) : 0.0;
}

struct MultisineSettings {
  int components = 1;
  double f_low = 0.0, f_high = 0.0, phase_offset = 0.0;
  bool scaled = false;  // to [low, high] over duration; else offset and equal amplitudes
  double low = 0.0, high = 0.0, duration = 0.0, offset = 0.0, amplitude = 0.0;
  double scanned = 0.0;  // unscaled: the run's duration, over which its range is checked
};

// Finding a multisine's range (MultisineSignal::range: to scale it to `range`, and for every
// check of a drive's or a load's signal over the run) scans 16 points per period of its fastest
// component over the duration, each summing every component. "" when that is within the limit
// (about a second), else why not.
std::string multisine_scan_problem(const MultisineSettings& s) {
  constexpr double kMaxTerms = 1e8;
  const double duration = s.scaled ? s.duration : s.scanned;
  const double points = std::ceil(duration * s.f_high * 16.0);
  const double terms = points * s.components;
  if (terms <= kMaxTerms) return {};
  return "finding the signal's range scans " + number_text(points) +
         " points (16 per period of the band's upper end over " + number_text(duration) +
         " s) of " + std::to_string(s.components) + " components = " + number_text(terms) +
         " terms, over the limit of " + number_text(kMaxTerms) +
         "; lower the band's upper end, the components or the duration";
}

std::unique_ptr<Signal> make_multisine(const MultisineSettings& s) {
  if (!(s.f_low < s.f_high)) throw std::invalid_argument("expected band lower < upper");
  if (const std::string problem = multisine_scan_problem(s); !problem.empty())
    throw std::invalid_argument(problem);
  const MultisineSignal unit_signal =
      MultisineSignal::schroeder(s.components, s.f_low, s.f_high, s.phase_offset);
  if (s.scaled) {
    if (!(s.low < s.high)) throw std::invalid_argument("expected range lower < upper");
    return std::make_unique<MultisineSignal>(unit_signal.scaled_to(s.low, s.high, s.duration));
  }
  return std::make_unique<MultisineSignal>(
      unit_signal.with_equal_amplitudes(s.offset, s.amplitude));
}

// The sequence is drawn whole when the scenario is read, a sample per 1/f_s: "" when its size
// is within the limit, else why not.
std::string random_steps_size_problem(const RandomStepsSettings& settings) {
  constexpr double kMaxSamples = 1e8;
  const double samples = settings.duration * settings.sample_rate;
  if (samples <= kMaxSamples) return {};
  return "duration x sample_rate = " + number_text(samples) + " samples, over the limit of " +
         number_text(kMaxSamples) +
         " (the sequence is drawn and held whole); lower the sample rate or the duration";
}

std::unique_ptr<Signal> make_random_steps(const RandomStepsSettings& settings, std::uint64_t seed,
                                          const std::string& purpose) {
  if (!(settings.low < settings.high)) throw std::invalid_argument("expected range lower < upper");
  if (const std::string problem = random_steps_size_problem(settings); !problem.empty())
    throw std::invalid_argument(problem);
  if (switching_probability(settings) > 1.0) {
    throw std::invalid_argument(
        "the switching probability 1/(0.5 tau_p f_s) exceeds 1; need tau_p >= 2/f_s");
  }
  RandomStream stream(seed, purpose);
  return make_random_steps(settings, stream);
}

std::unique_ptr<Signal> make_log_sweep(double offset, double amplitude, double f_start,
                                       double f_end, double duration) {
  if (!(f_start < f_end)) throw std::invalid_argument("expected band lower < upper");
  return std::make_unique<LogSweepSignal>(offset, amplitude, f_start, f_end, duration);
}

std::unique_ptr<Signal> make_sequence(Values durations, Parts parts) {
  std::vector<SequenceSignal::Segment> built;
  double start = 0.0;
  for (std::size_t k = 0; k < parts.size(); ++k) {
    built.push_back({start, std::move(parts[k])});
    start += durations[k];
  }
  return std::make_unique<SequenceSignal>(std::move(built));
}

}  // namespace

namespace signal_readers {

std::unique_ptr<Signal> constant(const ConfigNode& node, std::string_view unit,
                                 const SignalContext&) {
  return constant_at(node.is_scalar() ? node : node.at("value"), unit);
}

std::unique_ptr<Signal> steps(const ConfigNode& node, std::string_view unit, const SignalContext&) {
  Declared declared;
  const double initial = declared.quantity(node, "initial", unit);
  const auto times_node = node.at("times");
  const auto times = declared.quantities(times_node, "s");
  const auto values_node = node.at("values");
  const auto values = declared.quantities(values_node, unit);
  if (times.size() != values.size()) {
    values_node.fail("expected as many values as times (" + std::to_string(times.size()) +
                     "), got " + std::to_string(values.size()));
  }
  for (std::size_t k = 1; k < times.size(); ++k) {
    if (!(times[k] > times[k - 1])) times_node.fail("step times must increase strictly");
  }
  const std::size_t n = times.size();
  return with_recipe(std::make_unique<PiecewiseConstantSignal>(initial, times, values),
                     std::move(declared), [n](Values v, Parts) {
                       const auto t = slice(v, 1, n);
                       require_increasing(t, "step times must increase strictly");
                       return std::make_unique<PiecewiseConstantSignal>(v[0], t,
                                                                        slice(v, 1 + n, n));
                     });
}

std::unique_ptr<Signal> ramp(const ConfigNode& node, std::string_view unit, const SignalContext&) {
  Declared declared;
  const double start = declared.quantity(node, "start_time", "s", ValueCheck::non_negative());
  const double end = declared.quantity(node, "end_time", "s");
  if (!(end > start)) node.at("end_time").fail("expected end_time after start_time");
  const double from = declared.quantity(node, "from", unit);
  const double to = declared.quantity(node, "to", unit);
  return with_recipe(make_ramp(start, end, from, to), std::move(declared),
                     [](Values v, Parts) { return make_ramp(v[0], v[1], v[2], v[3]); });
}

std::unique_ptr<Signal> piecewise_linear(const ConfigNode& node, std::string_view unit,
                                         const SignalContext&) {
  Declared declared;
  const auto times_node = node.at("times");
  const auto times = declared.quantities(times_node, "s");
  const auto values_node = node.at("values");
  const auto values = declared.quantities(values_node, unit);
  if (times.empty() || times.size() != values.size()) {
    values_node.fail("expected as many values as times, and at least one");
  }
  for (std::size_t k = 1; k < times.size(); ++k) {
    if (!(times[k] > times[k - 1])) times_node.fail("times must increase strictly");
  }
  const std::size_t n = times.size();
  return with_recipe(std::make_unique<PiecewiseLinearSignal>(times, values), std::move(declared),
                     [n](Values v, Parts) {
                       const auto t = slice(v, 0, n);
                       require_increasing(t, "times must increase strictly");
                       return std::make_unique<PiecewiseLinearSignal>(t, slice(v, n, n));
                     });
}

std::unique_ptr<Signal> staircase(const ConfigNode& node, std::string_view unit,
                                  const SignalContext&) {
  Declared declared;
  const auto levels_node = node.at("levels");
  const auto levels = declared.quantities(levels_node, unit);
  if (levels.empty()) levels_node.fail("expected at least one level");
  const double hold = declared.quantity(node, "hold", "s", ValueCheck::positive());
  const double rate = declared.quantity(node, "rate", per_second(unit), ValueCheck::positive());
  const double start =
      declared.quantity_or(node, "start_time", "s", 0.0, ValueCheck::non_negative());
  const std::size_t n = levels.size();
  return with_recipe(
      make_staircase(levels, hold, rate, start), std::move(declared),
      [n](Values v, Parts) { return make_staircase(slice(v, 0, n), v[n], v[n + 1], v[n + 2]); });
}

std::unique_ptr<Signal> sine(const ConfigNode& node, std::string_view unit,
                             const SignalContext& context) {
  RandomStream stream(context.seed, node.path());
  Declared declared;
  const double offset = declared.quantity(node, "offset", unit);
  const double amplitude = declared.quantity(node, "amplitude", unit);
  const double frequency = declared.quantity(node, "frequency", "Hz", ValueCheck::positive());
  const std::size_t before = declared.list.size();
  const double phase = read_phase(node, "phase", stream, false, declared);
  const bool phase_is_parameter = declared.list.size() > before;
  return with_recipe(std::make_unique<SineSignal>(offset, amplitude, frequency, phase),
                     std::move(declared), [phase, phase_is_parameter](Values v, Parts) {
                       return std::make_unique<SineSignal>(v[0], v[1], v[2],
                                                           phase_is_parameter ? v[3] : phase);
                     });
}

std::unique_ptr<Signal> multisine(const ConfigNode& node, std::string_view unit,
                                  const SignalContext& context) {
  Declared declared;
  MultisineSettings s;
  s.components = static_cast<int>(node.integer(
      "components", ValueCheck::count(1e6, "every evaluation of the signal sums each component")));
  std::tie(s.f_low, s.f_high) = declared.interval(node, "band", "Hz", ValueCheck::positive());
  RandomStream stream(context.seed, node.path());
  const std::size_t before = declared.list.size();
  s.phase_offset = read_phase(node, "phase_offset", stream, true, declared);
  const bool phase_is_parameter = declared.list.size() > before;
  s.scaled = node.has("range");
  if (s.scaled) {
    std::tie(s.low, s.high) = declared.interval(node, "range", unit);
    s.duration =
        declared.quantity_or(node, "duration", "s", context.duration, ValueCheck::positive());
  } else {
    s.offset = declared.quantity(node, "offset", unit);
    s.amplitude = declared.quantity(node, "amplitude", unit);
    s.scanned = context.duration;
  }
  if (const std::string problem = multisine_scan_problem(s); !problem.empty())
    node.at("band").fail(problem);
  return with_recipe(make_multisine(s), std::move(declared),
                     [s, phase_is_parameter](Values v, Parts) {
                       MultisineSettings changed = s;
                       std::size_t k = 0;
                       changed.f_low = v[k++];
                       changed.f_high = v[k++];
                       if (phase_is_parameter) changed.phase_offset = v[k++];
                       if (s.scaled) {
                         changed.low = v[k++], changed.high = v[k++], changed.duration = v[k++];
                       } else {
                         changed.offset = v[k++], changed.amplitude = v[k++];
                       }
                       return make_multisine(changed);
                     });
}

std::unique_ptr<Signal> random_steps(const ConfigNode& node, std::string_view unit,
                                     const SignalContext& context) {
  Declared declared;
  RandomStepsSettings settings;
  std::tie(settings.low, settings.high) = declared.interval(node, "range", unit);
  settings.process_time_constant =
      declared.quantity(node, "process_time_constant", "s", ValueCheck::positive());
  settings.sample_rate = declared.quantity(node, "sample_rate", "Hz", ValueCheck::positive());
  settings.max_step_fraction =
      declared.quantity_or(node, "max_step_fraction", "1", 0.25, ValueCheck::fraction());
  settings.scale_to_range = node.boolean_or("scale_to_range", true);
  settings.duration =
      declared.quantity_or(node, "duration", "s", context.duration, ValueCheck::positive());
  if (const std::string problem = random_steps_size_problem(settings); !problem.empty())
    node.at("sample_rate").fail(problem);
  if (switching_probability(settings) > 1.0) {
    node.at("process_time_constant")
        .fail("the switching probability 1/(0.5 tau_p f_s) exceeds 1; need tau_p >= 2/f_s = " +
              std::to_string(2.0 / settings.sample_rate) + " s");
  }
  const std::uint64_t seed = context.seed;
  const std::string purpose = node.path();
  return with_recipe(make_random_steps(settings, seed, purpose), std::move(declared),
                     [settings, seed, purpose](Values v, Parts) {
                       RandomStepsSettings changed = settings;
                       changed.low = v[0], changed.high = v[1];
                       changed.process_time_constant = v[2], changed.sample_rate = v[3];
                       changed.max_step_fraction = v[4], changed.duration = v[5];
                       return make_random_steps(changed, seed, purpose);
                     });
}

std::unique_ptr<Signal> log_sweep(const ConfigNode& node, std::string_view unit,
                                  const SignalContext& context) {
  Declared declared;
  const auto [f_start, f_end] = declared.interval(node, "band", "Hz", ValueCheck::positive());
  const double offset = declared.quantity(node, "offset", unit);
  const double amplitude = declared.quantity(node, "amplitude", unit);
  const double duration =
      declared.quantity_or(node, "duration", "s", context.duration, ValueCheck::positive());
  return with_recipe(make_log_sweep(offset, amplitude, f_start, f_end, duration),
                     std::move(declared),
                     [](Values v, Parts) { return make_log_sweep(v[2], v[3], v[0], v[1], v[4]); });
}

std::unique_ptr<Signal> sequence(const ConfigNode& node, std::string_view unit,
                                 const SignalContext& context) {
  const auto segments_node = node.at("segments");
  const auto segments = segments_node.elements();
  if (segments.empty()) segments_node.fail("expected at least one segment");
  Declared declared;
  Parts parts;
  std::vector<std::shared_ptr<const SignalRecipe>> recipes;
  std::vector<double> durations;
  double start = 0.0;
  for (std::size_t k = 0; k < segments.size(); ++k) {
    const bool last = k + 1 == segments.size();
    const double duration =
        last ? declared.quantity_or(segments[k], "duration", "s",
                                    std::max(context.duration - start, 0.0),
                                    ValueCheck::non_negative())
             : declared.quantity(segments[k], "duration", "s", ValueCheck::positive());
    SignalContext inner = context;
    inner.duration = duration;
    parts.push_back(read_signal(segments[k].at("signal"), unit, inner));
    recipes.push_back(parts.back()->recipe());
    durations.push_back(duration);
    start += duration;
  }
  return with_recipe(make_sequence(durations, std::move(parts)), std::move(declared), make_sequence,
                     std::move(recipes));
}

std::unique_ptr<Signal> periodic(const ConfigNode& node, std::string_view unit,
                                 const SignalContext& context) {
  Declared declared;
  const double period = declared.quantity(node, "period", "s", ValueCheck::positive());
  SignalContext inner = context;
  inner.duration = period;
  auto part = read_signal(node.at("signal"), unit, inner);
  auto recipe = part->recipe();
  return with_recipe(std::make_unique<PeriodicSignal>(period, std::move(part)), std::move(declared),
                     [](Values v, Parts parts) {
                       return std::make_unique<PeriodicSignal>(v[0], std::move(parts.front()));
                     },
                     {recipe});
}

// The thesis' control-task references (7.3.4): a stepped sine sweep (15 log-spaced frequencies
// in [10^-2.4, 10^-1.1] Hz, 3 periods each) and a step sequence (7 levels held 20 s).
std::unique_ptr<Signal> stepped_sine_sweep(const ConfigNode& node, std::string_view unit,
                                           const SignalContext&) {
  node.declare({"type", "offset", "amplitude", "band", "frequencies", "periods", "start_time"});
  Declared declared;
  SineSweepSettings settings;
  settings.offset = declared.quantity(node, "offset", unit);
  settings.amplitude = declared.quantity(node, "amplitude", unit);
  const bool band = node.has("band");
  if (band) {
    std::tie(settings.lowest_frequency, settings.highest_frequency) =
        declared.interval(node, "band", "Hz", ValueCheck::positive());
  }
  settings.frequencies = static_cast<int>(
      node.integer_or("frequencies", settings.frequencies,
                      ValueCheck::count(1e4, "the sweep dwells a number of periods on each")));
  settings.periods =
      declared.quantity_or(node, "periods", "1", settings.periods, ValueCheck::positive());
  settings.start_time =
      declared.quantity_or(node, "start_time", "s", 0.0, ValueCheck::non_negative());
  return with_recipe(make_stepped_sine_sweep(settings), std::move(declared),
                     [settings, band](Values v, Parts) {
                       SineSweepSettings changed = settings;
                       std::size_t k = 0;
                       changed.offset = v[k++], changed.amplitude = v[k++];
                       if (band) {
                         changed.lowest_frequency = v[k++], changed.highest_frequency = v[k++];
                         if (!(changed.lowest_frequency < changed.highest_frequency))
                           throw std::invalid_argument("expected band lower < upper");
                       }
                       changed.periods = v[k++], changed.start_time = v[k++];
                       return make_stepped_sine_sweep(changed);
                     });
}

std::unique_ptr<Signal> step_sequence(const ConfigNode& node, std::string_view unit,
                                      const SignalContext&) {
  node.declare({"type", "range", "steps", "hold", "start_time", "initial"});
  Declared declared;
  StepSequenceSettings settings;
  std::tie(settings.low, settings.high) = declared.interval(node, "range", unit);
  settings.steps =
      static_cast<int>(node.integer_or("steps", settings.steps, ValueCheck::at_least(2)));
  settings.hold = declared.quantity_or(node, "hold", "s", settings.hold, ValueCheck::positive());
  settings.start_time =
      declared.quantity_or(node, "start_time", "s", 0.0, ValueCheck::non_negative());
  const bool initial = node.has("initial");
  if (initial) settings.initial = declared.quantity(node, "initial", unit);
  return with_recipe(make_step_sequence(settings), std::move(declared),
                     [settings, initial](Values v, Parts) {
                       StepSequenceSettings changed = settings;
                       changed.low = v[0], changed.high = v[1];
                       if (!(changed.low < changed.high))
                         throw std::invalid_argument("expected range lower < upper");
                       changed.hold = v[2], changed.start_time = v[3];
                       if (initial) changed.initial = v[4];
                       return make_step_sequence(changed);
                     });
}

}  // namespace signal_readers

}  // namespace tcpmsim
