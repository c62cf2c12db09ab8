#pragma once

#include <memory>
#include <vector>

#include "sim/signal.h"

namespace tcpmsim {

// Signals one after another; each runs on its own clock starting at 0 when its segment starts.
// The last segment lasts until the end of the run.
class SequenceSignal final : public Signal {
 public:
  struct Segment {
    double start;
    std::unique_ptr<Signal> signal;
  };
  explicit SequenceSignal(std::vector<Segment> segments);
  double value(double time) const override;
  double next_breakpoint_after(double time) const override;
  SignalDescription describe() const override;
  std::pair<double, double> range(double begin, double end) const override;

 private:
  std::size_t segment_at(double time) const;
  std::vector<Segment> segments_;
};

}  // namespace tcpmsim
