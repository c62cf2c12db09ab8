#pragma once

#include <memory>
#include <string>
#include <vector>

#include "models/laws/impedance.h"
#include "sim/component.h"
#include "sim/signal.h"

namespace tcpmsim::testing {

// Publishes a prescribed signal as output "value", sampled as the engine dictates (the left
// limit at breakpoints), and declares the signal's discontinuities.
class SignalSource final : public Component {
 public:
  SignalSource(std::string group, std::unique_ptr<Signal> signal);
  std::vector<OutputDeclaration> outputs() const override;
  std::vector<SignalDeclaration> signals() const override;
  void compute_outputs(const Evaluation& evaluation) const override;
  double next_breakpoint_after(const Evaluation& evaluation) const override;

 private:
  std::unique_ptr<Signal> signal_;
};

// The plant's L* ("sensor.inductance_measure") from its deflection by (7.3), without the
// Muscle Drive's artefacts.
class DecayTimeSensor final : public Component {
 public:
  explicit DecayTimeSensor(InductanceLaw law);
  std::vector<OutputDeclaration> outputs() const override;
  std::vector<InputDeclaration> inputs() const override;
  void compute_outputs(const Evaluation& evaluation) const override;

 private:
  InductanceLaw law_;
};

}  // namespace tcpmsim::testing
