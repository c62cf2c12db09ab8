#include "signals/sequence_signal.h"

#include <algorithm>
#include <stdexcept>

namespace tcpmsim {

SequenceSignal::SequenceSignal(std::vector<Segment> segments) : segments_(std::move(segments)) {
  if (segments_.empty()) throw std::invalid_argument("sequence: no segments");
}

std::size_t SequenceSignal::segment_at(double time) const {
  std::size_t k = 0;
  while (k + 1 < segments_.size() && time >= segments_[k + 1].start) ++k;
  return k;
}

double SequenceSignal::value(double time) const {
  const auto& segment = segments_[segment_at(time)];
  return segment.signal->value(time - segment.start);
}

double SequenceSignal::next_breakpoint_after(double time) const {
  const std::size_t k = segment_at(time);
  const double start = segments_[k].start;
  // Shifting a piece's breakpoint back to global time may round it onto `time`: skip those.
  double local = segments_[k].signal->next_breakpoint_after(time - start);
  while (local != kNoBreakpoint && start + local <= time) {
    local = segments_[k].signal->next_breakpoint_after(local);
  }
  double next = local == kNoBreakpoint ? kNoBreakpoint : start + local;
  if (k + 1 < segments_.size()) next = std::min(next, segments_[k + 1].start);
  return next;
}

SignalDescription SequenceSignal::describe() const {
  SignalDescription description{"sequence", {}, {}, {}};
  std::vector<double> starts;
  for (std::size_t k = 0; k < segments_.size(); ++k) {
    starts.push_back(segments_[k].start);
    description.parts.push_back({"segment" + std::to_string(k), segments_[k].signal->describe()});
  }
  description.arrays.emplace_back("starts", starts);
  return description;
}

std::pair<double, double> SequenceSignal::range(double begin, double end) const {
  double low = value(begin), high = low;
  for (std::size_t k = 0; k < segments_.size(); ++k) {
    const double from = std::max(begin, segments_[k].start);
    const double to = k + 1 < segments_.size() ? std::min(end, segments_[k + 1].start) : end;
    if (from > to) continue;
    const auto [l, h] =
        segments_[k].signal->range(from - segments_[k].start, to - segments_[k].start);
    low = std::min(low, l);
    high = std::max(high, h);
  }
  return {low, high};
}

}  // namespace tcpmsim
