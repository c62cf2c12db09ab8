#include "models/imposed_load.h"

namespace tcpmsim {

ImposedLoad::ImposedLoad(std::string group, Quantity quantity, std::unique_ptr<Signal> signal)
    : Component(std::move(group),
                quantity == Quantity::deflection ? "imposed_deflection" : "imposed_force"),
      quantity_(quantity),
      signal_(std::move(signal)) {}

std::vector<OutputDeclaration> ImposedLoad::outputs() const {
  if (quantity_ == Quantity::deflection) return {{"deflection", "m"}};
  return {{"force", "N"}};
}

std::vector<SignalDeclaration> ImposedLoad::signals() const {
  if (quantity_ == Quantity::deflection) return {{"deflection", "m", signal_.get()}};
  return {{"force", "N", signal_.get()}};
}

void ImposedLoad::compute_outputs(const Evaluation& evaluation) const {
  set_output(evaluation, 0, signal(evaluation, 0).value(evaluation.signal_time));
}

double ImposedLoad::next_breakpoint_after(const Evaluation& evaluation) const {
  return signal(evaluation, 0).next_breakpoint_after(evaluation.time);
}

}  // namespace tcpmsim
