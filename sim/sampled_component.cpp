#include "sim/sampled_component.h"

#include "sim/time_grid.h"

namespace tcpmsim {

SampledComponent::SampledComponent(std::string group, std::string kind, double period,
                                   SamplingStage stage)
    : Component(std::move(group), std::move(kind)), period_(period), stage_(stage) {}

double SampledComponent::next_breakpoint_after(double t) const {
  return next_grid_instant(t, period_);
}

void SampledComponent::at_breakpoint(const Evaluation& evaluation) {
  if (const auto k = grid_index_at(evaluation.time, period_)) sample(evaluation, *k);
}

}  // namespace tcpmsim
