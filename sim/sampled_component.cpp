#include "sim/sampled_component.h"

#include "sim/time_grid.h"

namespace tcpmsim {

SampledComponent::SampledComponent(std::string group, std::string kind, double period,
                                   SamplingStage stage)
    : Component(std::move(group), std::move(kind)), period_(period), stage_(stage) {}

std::vector<ParameterDeclaration> SampledComponent::parameters() const {
  return {{group() + ".sample_period", "s", period_, ValueCheck::positive(), {}}};
}

std::vector<ParameterDeclaration> SampledComponent::with_period(
    std::vector<ParameterDeclaration> own) const {
  auto declared = SampledComponent::parameters();
  for (auto& parameter : own) declared.push_back(std::move(parameter));
  return declared;
}

double SampledComponent::next_breakpoint_after(const Evaluation& evaluation) const {
  return next_grid_instant(evaluation.time, period(evaluation));
}

void SampledComponent::at_breakpoint(const Evaluation& evaluation) const {
  if (const auto k = grid_index_at(evaluation.time, period(evaluation))) sample(evaluation, *k);
}

}  // namespace tcpmsim
