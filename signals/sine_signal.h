#pragma once

#include "sim/signal.h"

namespace tcpmsim {

// offset + amplitude sin(2 pi f t + phase).
class SineSignal final : public Signal {
 public:
  SineSignal(double offset, double amplitude, double frequency, double phase);
  double value(double time) const override;
  double slope(double time) const override;
  SignalDescription describe() const override;
  std::pair<double, double> range(double begin, double end) const override;

 private:
  double offset_, amplitude_, frequency_, phase_;
};

}  // namespace tcpmsim
