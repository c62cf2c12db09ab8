#pragma once

#include <memory>

#include "sim/signal.h"

namespace tcpmsim {

// Repeats a signal every `period` (its clock restarts at 0 each period): a test protocol run
// once per temperature, a duty pattern per PWM period.
class PeriodicSignal final : public Signal {
 public:
  PeriodicSignal(double period, std::unique_ptr<Signal> signal);
  double value(double time) const override;
  double next_breakpoint_after(double time) const override;
  SignalDescription describe() const override;
  std::pair<double, double> range(double begin, double end) const override;

 private:
  double period_;
  std::unique_ptr<Signal> signal_;
};

}  // namespace tcpmsim
