#include "signals/sine_signal.h"

#include <cmath>
#include <numbers>

namespace tcpmsim {

SineSignal::SineSignal(double offset, double amplitude, double frequency, double phase)
    : offset_(offset), amplitude_(amplitude), frequency_(frequency), phase_(phase) {}

double SineSignal::value(double time) const {
  return offset_ + amplitude_ * std::sin(2.0 * std::numbers::pi * frequency_ * time + phase_);
}

double SineSignal::slope(double time) const {
  const double omega = 2.0 * std::numbers::pi * frequency_;
  return amplitude_ * omega * std::cos(omega * time + phase_);
}

SignalDescription SineSignal::describe() const {
  return {"sine",
          {{"offset", offset_},
           {"amplitude", amplitude_},
           {"frequency", frequency_},
           {"phase", phase_}},
          {},
          {}};
}

std::pair<double, double> SineSignal::range(double, double) const {
  const double reach = std::abs(amplitude_);
  return {offset_ - reach, offset_ + reach};
}

}  // namespace tcpmsim
