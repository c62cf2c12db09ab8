#pragma once

#include <vector>

#include "sim/signal.h"

namespace tcpmsim {

// m(t) = a0 + sum_i a_i sin(2 pi f_i t + phi_i)   (7.11)
class MultisineSignal final : public Signal {
 public:
  MultisineSignal(double offset, std::vector<double> amplitudes, std::vector<double> frequencies,
                  std::vector<double> phases);

  // N equally spaced frequencies in [f_low, f_high] with the Schroeder phases of (7.12),
  // phi_i = phi_0 - pi i^2 / N, and unit amplitudes.
  static MultisineSignal schroeder(int components, double f_low, double f_high,
                                   double phase_offset);
  // The same frequencies with the given phases.
  static std::vector<double> equally_spaced(int components, double f_low, double f_high);

  // Scales equal amplitudes and the offset so that the signal spans exactly [low, high] over
  // [0, duration], as the thesis scales its excitations to the actuator limits.
  MultisineSignal scaled_to(double low, double high, double duration) const;
  // The same frequencies and phases with all amplitudes equal to `amplitude`.
  MultisineSignal with_equal_amplitudes(double offset, double amplitude) const;

  double value(double time) const override;
  double slope(double time) const override;
  SignalDescription describe() const override;
  std::pair<double, double> range(double begin, double end) const override;
  // max |m - a0| / rms(m - a0) over [0, duration]
  double crest_factor(double duration) const;

 private:
  double offset_;
  std::vector<double> amplitudes_, frequencies_, phases_;
  // Equally spaced frequencies (the thesis' construction) allow evaluating all components with
  // two sin/cos pairs and a rotation recurrence instead of one sin per component.
  bool equally_spaced_ = false;
  std::vector<double> cos_phase_, sin_phase_;
};

}  // namespace tcpmsim
