#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "signals/piecewise_constant_signal.h"
#include "sim/signal.h"

namespace tcpmsim {

// The references of the thesis' control tasks (section 7.3.4): a step sequence and a stepped
// sine sweep. Factories for C++; the YAML keys are read elsewhere (signals/signal_readers.cpp).

// When and at which frequency each sine of a stepped sweep runs.
struct SweepSchedule {
  std::vector<double> frequencies;  // [Hz], in the order applied
  std::vector<double> start_times;  // [s], when each frequency starts
  double periods = 3.0;             // periods of each frequency
  double end_time(std::size_t index) const {
    return start_times[index] + periods / frequencies[index];
  }
};

// A stepped sine sweep: frequency f_i for `periods` periods from start_times[i], the next
// frequency starting where the previous one ends:
//     value = offset + amplitude sin(2 pi f_i (t - t_i))   on [t_i, t_i + periods / f_i),
// and `offset` before the first and after the last. Every frequency starts at zero phase, so
// the value is continuous; its slope jumps at the segment boundaries, which are breakpoints.
class SteppedSineSignal final : public Signal {
 public:
  SteppedSineSignal(double offset, double amplitude, SweepSchedule schedule);
  double value(double time) const override;
  double slope(double time) const override;
  double next_breakpoint_after(double time) const override;
  SignalDescription describe() const override;
  std::pair<double, double> range(double begin, double end) const override;

  const SweepSchedule& schedule() const { return schedule_; }
  double offset() const { return offset_; }
  double amplitude() const { return amplitude_; }
  double end_time() const;

 private:
  // The segment holding `time`, or -1 outside the sweep.
  long segment_at(double time) const;

  double offset_;
  double amplitude_;
  SweepSchedule schedule_;
};

struct SineSweepSettings {
  double offset = 0.0;
  double amplitude = 0.0;
  double lowest_frequency = 3.9810717055349725e-3;   // 10^-2.4 Hz
  double highest_frequency = 7.9432823472428138e-2;  // 10^-1.1 Hz
  int frequencies = 15;
  double periods = 3.0;
  double start_time = 0.0;
};

// 15 log-spaced frequencies from lowest to highest (f_i = f_low (f_high / f_low)^(i / (n - 1))),
// 3 periods each, one after another: the thesis' sine sweep (0.05 N around 0.40 N for force,
// 5 mm around 20 mm for deflection). It lasts 3 sum(1/f_i) = 3756 s with the defaults.
std::unique_ptr<SteppedSineSignal> make_stepped_sine_sweep(const SineSweepSettings& settings);

struct StepSequenceSettings {
  double low = 0.0;  // the range the levels spread over
  double high = 0.0;
  int steps = 7;
  double hold = 20.0;             // [s] each level is held
  double start_time = 0.0;        // the first step [s]
  std::optional<double> initial;  // the value before the first step; default (low + high) / 2
};

// The levels of a step sequence, in the order visited. The thesis gives the number of steps,
// the range and the hold but not the levels; we take `steps` equally spaced levels
// l_j = low + j (high - low) / (steps - 1) and visit them from the outside in, alternating
// ends: l_0, l_{n-1}, l_1, l_{n-2}, ... For 7 levels the steps after the first are 6, 5, 4, 3,
// 2 and 1 sixths of the range, alternating in direction: the spread of step sizes the thesis
// uses to explain its spread of rise times (7.5).
std::vector<double> step_sequence_levels(double low, double high, int steps);

// Level j of step_sequence_levels from start_time + j hold, each held for `hold`; the last level
// stays after the end (start_time + steps hold).
std::unique_ptr<PiecewiseConstantSignal> make_step_sequence(const StepSequenceSettings& settings);

}  // namespace tcpmsim
