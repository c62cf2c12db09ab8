#include "models/effects/ratchet.h"

#include "models/typical_values.h"

namespace tcpmsim {

Ratchet::Ratchet(std::string group, RatchetParameters defaults,
                 ParameterBindings<RatchetParameters> bindings)
    : ParametricComponent(std::move(group), "ratchet", defaults, std::move(bindings)) {}

std::unique_ptr<Ratchet> Ratchet::from_config(const std::string& group, const ConfigNode& node) {
  using P = RatchetParameters;
  node.declare({"type", "name", "rate", "threshold"});
  P p;
  ParameterBindings<P> bind;
  bind.quantity(node, "rate", "N/(K*s)", ValueCheck::non_negative(), p, bind.member(&P::rate));
  bind.quantity(node, "threshold", "K", typical::temperature(ValueCheck::positive()), p,
                bind.member(&P::threshold));
  return std::make_unique<Ratchet>(group, p, std::move(bind));
}

std::vector<OutputDeclaration> Ratchet::outputs() const {
  return {{"stiffness", "N/m", false, false},
          {"offset_force", "N", false, false},
          {"rest_stiffness", "N/m", false, false},
          {"rest_force", "N", false, false},
          {"force", "N"}};
}

void Ratchet::initialize(const Evaluation&, std::span<double> own_state) const {
  own_state[0] = 0.0;
}

void Ratchet::compute_outputs(const Evaluation& evaluation) const {
  const double force = state(evaluation, 0);
  set_output(evaluation, kStiffness, 0.0);
  set_output(evaluation, kOffsetForce, force);
  set_output(evaluation, kRestStiffness, 0.0);
  set_output(evaluation, kRestForce, 0.0);
  set_output(evaluation, kForce, force);
}

void Ratchet::compute_derivatives(const Evaluation& evaluation, double* derivatives) const {
  set_derivative(derivatives, 0,
                 ratchet::force_rate(run_parameters(evaluation), input(evaluation, kTemperature)));
}

}  // namespace tcpmsim
