#include "signals/log_sweep_signal.h"

#include <cmath>
#include <numbers>

namespace tcpmsim {

LogSweepSignal::LogSweepSignal(double offset, double amplitude, double f_start, double f_end,
                               double duration)
    : offset_(offset),
      amplitude_(amplitude),
      f_start_(f_start),
      f_end_(f_end),
      duration_(duration) {}

double LogSweepSignal::value(double time) const {
  if (time < 0.0 || time >= duration_) return offset_;
  const double rate = std::log(f_end_ / f_start_);
  const double phase = 2.0 * std::numbers::pi * f_start_ * duration_ / rate *
                       (std::exp(time * rate / duration_) - 1.0);
  return offset_ + amplitude_ * std::sin(phase);
}

double LogSweepSignal::instantaneous_frequency(double time) const {
  return f_start_ * std::exp(time / duration_ * std::log(f_end_ / f_start_));
}

double LogSweepSignal::next_breakpoint_after(double time) const {
  if (time < 0.0) return 0.0;
  return time < duration_ ? duration_ : kNoBreakpoint;
}

SignalDescription LogSweepSignal::describe() const {
  return {"log_sweep",
          {{"offset", offset_},
           {"amplitude", amplitude_},
           {"start_frequency", f_start_},
           {"end_frequency", f_end_},
           {"duration", duration_}},
          {},
          {}};
}

std::pair<double, double> LogSweepSignal::range(double, double) const {
  const double reach = std::abs(amplitude_);
  return {offset_ - reach, offset_ + reach};
}

}  // namespace tcpmsim
