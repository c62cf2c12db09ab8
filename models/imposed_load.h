#pragma once

#include <memory>

#include "sim/component.h"
#include "sim/signal.h"

namespace tcpmsim {

// A testing machine that prescribes one mechanical quantity: the deflection (position mode) or
// the force (force mode), following a signal.
class ImposedLoad final : public Component {
 public:
  enum class Quantity { deflection, force };
  ImposedLoad(std::string group, Quantity quantity, std::unique_ptr<Signal> signal);

  std::vector<OutputDeclaration> outputs() const override;
  std::vector<SignalDeclaration> signals() const override;
  void compute_outputs(const Evaluation& evaluation) const override;
  double next_breakpoint_after(const Evaluation& evaluation) const override;

 private:
  Quantity quantity_;
  std::unique_ptr<Signal> signal_;
};

}  // namespace tcpmsim
