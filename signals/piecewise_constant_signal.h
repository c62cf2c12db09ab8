#pragma once

#include <vector>

#include "sim/signal.h"

namespace tcpmsim {

// Steps: `initial` before the first time, values[k] from times[k] on. Also the realisation
// of random-step (generalised binary noise) signals.
class PiecewiseConstantSignal final : public Signal {
 public:
  PiecewiseConstantSignal(double initial, std::vector<double> times, std::vector<double> values,
                          SignalDescription description = {});
  double value(double time) const override;
  double next_breakpoint_after(double time) const override;
  double slope(double) const override { return 0.0; }
  SignalDescription describe() const override;
  std::pair<double, double> range(double begin, double end) const override;

  const std::vector<double>& times() const { return times_; }
  const std::vector<double>& values() const { return values_; }

 private:
  double initial_;
  std::vector<double> times_;
  std::vector<double> values_;
  SignalDescription description_;
};

}  // namespace tcpmsim
