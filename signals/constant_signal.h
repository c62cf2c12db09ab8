#pragma once

#include "sim/signal.h"

namespace tcpmsim {

class ConstantSignal final : public Signal {
 public:
  explicit ConstantSignal(double value) : value_(value) {}
  double value(double) const override { return value_; }
  double slope(double) const override { return 0.0; }
  SignalDescription describe() const override;
  std::pair<double, double> range(double, double) const override { return {value_, value_}; }

 private:
  double value_;
};

}  // namespace tcpmsim
