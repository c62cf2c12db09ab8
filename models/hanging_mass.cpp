#include "models/hanging_mass.h"
#include "models/typical_values.h"

namespace tcpmsim {

HangingMass::HangingMass(std::string group, HangingMassParameters defaults,
                         ParameterBindings<HangingMassParameters> bindings)
    : ParametricComponent(std::move(group), "hanging_mass", defaults, std::move(bindings)) {}

std::unique_ptr<HangingMass> HangingMass::from_config(
    const std::string& group, const ConfigNode& node,
    const std::function<double(double weight)>& equilibrium) {
  using P = HangingMassParameters;
  P p;
  ParameterBindings<P> bind;
  bind.quantity(node, "mass", "kg", typical::mass(ValueCheck::positive()), p,
                bind.member(&P::mass));
  bind.quantity_or(node, "gravity", "m/s^2", p.gravity, ValueCheck::non_negative(), p,
                   bind.member(&P::gravity));
  bind.quantity_or(node, "damping", "N*s/m", 0.0, ValueCheck::non_negative(), p,
                   bind.member(&P::damping));
  const ConfigNode initial = node.at("initial_deflection");
  if (initial.is_word("equilibrium")) {
    p.initial_deflection = equilibrium(p.mass * p.gravity);
    bind.bind(initial.parameter_path(), "m", {}, bind.member(&P::initial_deflection));
  } else {
    bind.as_quantity(initial, "m", {}, p, bind.member(&P::initial_deflection));
  }
  node.describe_key("initial_deflection", "quantity in m, or equilibrium");
  bind.quantity_or(node, "initial_velocity", "m/s", 0.0, {}, p, bind.member(&P::initial_velocity));
  return std::make_unique<HangingMass>(group, p, std::move(bind));
}

void HangingMass::initialize(const Evaluation& evaluation, std::span<double> own_state) const {
  const auto& p = run_parameters(evaluation);
  own_state[0] = p.initial_deflection;
  own_state[1] = p.initial_velocity;
}

void HangingMass::compute_outputs(const Evaluation& evaluation) const {
  set_output(evaluation, kDeflection, state(evaluation, 0));
  set_output(evaluation, kVelocity, state(evaluation, 1));
}

void HangingMass::compute_derivatives(const Evaluation& evaluation, double* derivatives) const {
  const auto& p = run_parameters(evaluation);
  const double velocity = state(evaluation, 1);
  const double weight = p.mass * p.gravity;
  set_derivative(derivatives, 0, velocity);
  set_derivative(derivatives, 1,
                 (weight - input_sum(evaluation, kMuscleForce) - p.damping * velocity) / p.mass);
}

}  // namespace tcpmsim
