#pragma once

#include <vector>

#include "sim/signal.h"

namespace tcpmsim {

// Straight lines between (time, value) points, constant outside them. Ramps and staircases.
class PiecewiseLinearSignal final : public Signal {
 public:
  PiecewiseLinearSignal(std::vector<double> times, std::vector<double> values,
                        std::string type = "piecewise_linear");
  double value(double time) const override;
  double next_breakpoint_after(double time) const override;
  SignalDescription describe() const override;
  std::pair<double, double> range(double begin, double end) const override;

 private:
  std::vector<double> times_;
  std::vector<double> values_;
  std::string type_;
};

}  // namespace tcpmsim
