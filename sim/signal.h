#pragma once

#include <string>
#include <utility>
#include <vector>

#include "sim/component.h"

namespace tcpmsim {

// What a signal is, in enough detail to rebuild it offline (written to /inputs in the HDF5).
struct SignalDescription {
  std::string type;
  std::vector<std::pair<std::string, double>> parameters;
  std::vector<std::pair<std::string, std::vector<double>>> arrays;
  std::vector<std::pair<std::string, SignalDescription>> parts;
};

// A prescribed function of time: an excitation applied to a duty cycle, a power, an imposed
// deflection or force, or an ambient temperature. Values are SI and right-continuous.
class Signal {
 public:
  virtual ~Signal() = default;
  virtual double value(double time) const = 0;
  // d value / dt (right derivative). The default differentiates numerically; smooth signals
  // override it exactly.
  virtual double slope(double time) const;
  // The first time strictly after `time` where the signal or its slope jumps.
  virtual double next_breakpoint_after(double time) const;
  virtual SignalDescription describe() const = 0;
  // Smallest and largest value over [begin, end], for validating against physical limits.
  virtual std::pair<double, double> range(double begin, double end) const = 0;
};

}  // namespace tcpmsim
