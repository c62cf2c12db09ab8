#include "signals/periodic_signal.h"

#include <algorithm>
#include <cmath>

namespace tcpmsim {

PeriodicSignal::PeriodicSignal(double period, std::unique_ptr<Signal> signal)
    : period_(period), signal_(std::move(signal)) {}

double PeriodicSignal::value(double time) const {
  const double cycle = std::floor(time / period_);
  return signal_->value(time - cycle * period_);
}

double PeriodicSignal::next_breakpoint_after(double time) const {
  const double cycle = std::floor(time / period_);
  const double start = cycle * period_;
  double inner = signal_->next_breakpoint_after(time - start);
  while (inner != kNoBreakpoint && start + inner <= time)
    inner = signal_->next_breakpoint_after(inner);
  const double end = start + period_ > time ? start + period_ : start + 2.0 * period_;
  return std::min(end, inner == kNoBreakpoint ? kNoBreakpoint : start + inner);
}

SignalDescription PeriodicSignal::describe() const {
  return {"periodic", {{"period", period_}}, {}, {{"signal", signal_->describe()}}};
}

std::pair<double, double> PeriodicSignal::range(double begin, double end) const {
  if (end - begin >= period_) return signal_->range(0.0, period_);
  const double start = std::floor(begin / period_) * period_;
  if (end <= start + period_) return signal_->range(begin - start, end - start);
  const auto [a_low, a_high] = signal_->range(begin - start, period_);
  const auto [b_low, b_high] = signal_->range(0.0, end - start - period_);
  return {std::min(a_low, b_low), std::max(a_high, b_high)};
}

}  // namespace tcpmsim
