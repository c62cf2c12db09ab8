#include "sim/sampled_component.h"

#include <cmath>
#include <limits>

namespace tcpmsim {

SampledComponent::SampledComponent(std::string group, std::string kind, double period,
                                   SamplingStage stage)
    : Component(std::move(group), std::move(kind)), period_(period), stage_(stage) {}

double SampledComponent::next_breakpoint_after(double t) const {
  // Instants are k * period, computed by multiplication so they never drift.
  double k = std::floor(t / period_) + 1.0;
  while (k * period_ <= t) k += 1.0;
  return k * period_;
}

void SampledComponent::at_breakpoint(const Evaluation& evaluation) {
  const double k = std::round(evaluation.time / period_);
  const double tolerance =
      64.0 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::abs(evaluation.time));
  if (std::abs(evaluation.time - k * period_) <= tolerance)
    sample(evaluation, static_cast<long>(k));
}

}  // namespace tcpmsim
