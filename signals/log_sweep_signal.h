#pragma once

#include "sim/signal.h"

namespace tcpmsim {

// Exponential (logarithmic) sine sweep from f_start to f_end over [0, duration] (Farina):
// x(t) = offset + A sin(2 pi f_start T / ln(f_end/f_start) (exp(t ln(f_end/f_start) / T) - 1)).
// Holds the offset outside the sweep.
class LogSweepSignal final : public Signal {
 public:
  LogSweepSignal(double offset, double amplitude, double f_start, double f_end, double duration);
  double value(double time) const override;
  double next_breakpoint_after(double time) const override;
  SignalDescription describe() const override;
  std::pair<double, double> range(double begin, double end) const override;
  double instantaneous_frequency(double time) const;

 private:
  double offset_, amplitude_, f_start_, f_end_, duration_;
};

}  // namespace tcpmsim
