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

void ImposedLoad::compute_outputs(const Evaluation& evaluation) const {
  set_output(evaluation, 0, signal_->value(evaluation.signal_time));
}

double ImposedLoad::next_breakpoint_after(double t) const {
  return signal_->next_breakpoint_after(t);
}

std::vector<Component::SignalRecord> ImposedLoad::signal_records() const {
  if (quantity_ == Quantity::deflection) return {{"deflection", "m", signal_.get()}};
  return {{"force", "N", signal_.get()}};
}

}  // namespace tcpmsim
