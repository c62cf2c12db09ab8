#include "signals/control_task_signals.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace tcpmsim {

namespace {
constexpr double kTwoPi = 2.0 * std::numbers::pi;

// Smallest and largest sin(theta) over [from, to].
std::pair<double, double> sine_extremes(double from, double to) {
  double low = std::min(std::sin(from), std::sin(to));
  double high = std::max(std::sin(from), std::sin(to));
  // A maximum at pi/2 + 2 pi k, a minimum at 3 pi/2 + 2 pi k, if inside.
  if (std::ceil((from - 0.5 * std::numbers::pi) / kTwoPi) <=
      std::floor((to - 0.5 * std::numbers::pi) / kTwoPi))
    high = 1.0;
  if (std::ceil((from - 1.5 * std::numbers::pi) / kTwoPi) <=
      std::floor((to - 1.5 * std::numbers::pi) / kTwoPi))
    low = -1.0;
  return {low, high};
}
}  // namespace

SteppedSineSignal::SteppedSineSignal(double offset, double amplitude, SweepSchedule schedule)
    : offset_(offset), amplitude_(amplitude), schedule_(std::move(schedule)) {
  const auto& f = schedule_.frequencies;
  const auto& t = schedule_.start_times;
  if (f.empty() || f.size() != t.size())
    throw std::invalid_argument(
        "stepped sine: need one start time per frequency, and one at least");
  if (!(schedule_.periods > 0.0)) throw std::invalid_argument("stepped sine: periods must be > 0");
  for (std::size_t i = 0; i < f.size(); ++i) {
    if (!(f[i] > 0.0) || !std::isfinite(f[i]))
      throw std::invalid_argument("stepped sine: frequencies must be positive");
    if (i > 0 && t[i] < schedule_.end_time(i - 1))
      throw std::invalid_argument("stepped sine: a frequency starts before the previous ends");
  }
}

long SteppedSineSignal::segment_at(double time) const {
  const auto& starts = schedule_.start_times;
  const auto after = std::upper_bound(starts.begin(), starts.end(), time);
  if (after == starts.begin()) return -1;
  const auto index = static_cast<std::size_t>(after - starts.begin() - 1);
  return time < schedule_.end_time(index) ? static_cast<long>(index) : -1;
}

double SteppedSineSignal::value(double time) const {
  const long segment = segment_at(time);
  if (segment < 0) return offset_;
  const auto i = static_cast<std::size_t>(segment);
  return offset_ + amplitude_ * std::sin(kTwoPi * schedule_.frequencies[i] *
                                         (time - schedule_.start_times[i]));
}

double SteppedSineSignal::slope(double time) const {
  const long segment = segment_at(time);
  if (segment < 0) return 0.0;
  const auto i = static_cast<std::size_t>(segment);
  const double omega = kTwoPi * schedule_.frequencies[i];
  return amplitude_ * omega * std::cos(omega * (time - schedule_.start_times[i]));
}

double SteppedSineSignal::next_breakpoint_after(double time) const {
  double next = kNoBreakpoint;
  for (std::size_t i = 0; i < schedule_.frequencies.size(); ++i) {
    for (const double edge : {schedule_.start_times[i], schedule_.end_time(i)}) {
      if (edge > time) next = std::min(next, edge);
    }
    if (next < kNoBreakpoint) break;  // edges increase with i
  }
  return next;
}

double SteppedSineSignal::end_time() const {
  return schedule_.end_time(schedule_.frequencies.size() - 1);
}

SignalDescription SteppedSineSignal::describe() const {
  return {"stepped_sine",
          {{"offset", offset_}, {"amplitude", amplitude_}, {"periods", schedule_.periods}},
          {{"frequencies", schedule_.frequencies}, {"start_times", schedule_.start_times}},
          {}};
}

std::pair<double, double> SteppedSineSignal::range(double begin, double end) const {
  double low = kNoBreakpoint, high = -kNoBreakpoint;
  auto include = [&](double value) {
    low = std::min(low, value);
    high = std::max(high, value);
  };
  // Time outside every segment shows the offset.
  double covered = begin;
  for (std::size_t i = 0; i < schedule_.frequencies.size(); ++i) {
    const double from = std::max(begin, schedule_.start_times[i]);
    const double to = std::min(end, schedule_.end_time(i));
    if (from > to) continue;
    if (from > covered) include(offset_);
    const double omega = kTwoPi * schedule_.frequencies[i];
    const auto [s_low, s_high] = sine_extremes(omega * (from - schedule_.start_times[i]),
                                               omega * (to - schedule_.start_times[i]));
    include(offset_ + amplitude_ * s_low);
    include(offset_ + amplitude_ * s_high);
    covered = to;
  }
  if (covered < end || low > high) include(offset_);
  return {low, high};
}

std::unique_ptr<SteppedSineSignal> make_stepped_sine_sweep(const SineSweepSettings& settings) {
  const int n = settings.frequencies;
  if (n < 1) throw std::invalid_argument("sine sweep: need at least one frequency");
  if (!(settings.lowest_frequency > 0.0) ||
      !(settings.highest_frequency >= settings.lowest_frequency))
    throw std::invalid_argument("sine sweep: need 0 < lowest <= highest frequency");
  SweepSchedule schedule;
  schedule.periods = settings.periods;
  double start = settings.start_time;
  const double ratio = settings.highest_frequency / settings.lowest_frequency;
  for (int i = 0; i < n; ++i) {
    const double f = n == 1 ? settings.lowest_frequency
                            : settings.lowest_frequency * std::pow(ratio, double(i) / (n - 1));
    schedule.frequencies.push_back(f);
    schedule.start_times.push_back(start);
    start = schedule.end_time(static_cast<std::size_t>(i));  // the same arithmetic as end_time
  }
  return std::make_unique<SteppedSineSignal>(settings.offset, settings.amplitude,
                                             std::move(schedule));
}

std::vector<double> step_sequence_levels(double low, double high, int steps) {
  if (steps < 2) throw std::invalid_argument("step sequence: need at least two steps");
  if (!(low < high)) throw std::invalid_argument("step sequence: need low < high");
  std::vector<double> levels;
  for (int j = 0; j < steps; ++j) {
    // From the outside in: 0, n-1, 1, n-2, ...
    const int index = j % 2 == 0 ? j / 2 : steps - 1 - j / 2;
    levels.push_back(low + (high - low) * index / (steps - 1));
  }
  return levels;
}

std::unique_ptr<PiecewiseConstantSignal> make_step_sequence(const StepSequenceSettings& settings) {
  if (!(settings.hold > 0.0)) throw std::invalid_argument("step sequence: hold must be > 0");
  const auto levels = step_sequence_levels(settings.low, settings.high, settings.steps);
  std::vector<double> times;
  for (int j = 0; j < settings.steps; ++j) times.push_back(settings.start_time + j * settings.hold);
  SignalDescription description{"step_sequence",
                                {{"low", settings.low},
                                 {"high", settings.high},
                                 {"steps", settings.steps},
                                 {"hold", settings.hold},
                                 {"start_time", settings.start_time}},
                                {},
                                {}};
  return std::make_unique<PiecewiseConstantSignal>(
      settings.initial.value_or(0.5 * (settings.low + settings.high)), std::move(times), levels,
      std::move(description));
}

}  // namespace tcpmsim
