#include "models/effects/hysteresis.h"

#include "models/typical_values.h"

namespace tcpmsim {

Hysteresis::Hysteresis(std::string group, HysteresisParameters defaults,
                       ParameterBindings<HysteresisParameters> bindings)
    : ParametricComponent(std::move(group), "hysteresis", defaults, std::move(bindings)) {}

std::unique_ptr<Hysteresis> Hysteresis::from_config(const std::string& group,
                                                    const ConfigNode& node) {
  using P = HysteresisParameters;
  node.declare({"type", "name", "stiffness", "force", "radius", "follower_time"});
  P p;
  ParameterBindings<P> bind;
  // A zero weight carries no force (discover's candidates start there).
  bind.quantity(node, "stiffness", "N/m", typical::added_stiffness(ValueCheck::non_negative()), p,
                bind.member(&P::stiffness));
  if (node.has("force") && node.has("radius"))
    node.at("radius").fail("give force or radius (= force / stiffness), not both");
  if (node.has("radius"))
    bind.quantity(node, "radius", "m", typical::muscle_length(ValueCheck::positive()), p,
                  bind.member(&P::radius));
  else
    bind.quantity(node, "force", "N", typical::effect_force(ValueCheck::positive()), p,
                  bind.member(&P::force));
  bind.quantity_or(node, "follower_time", "s", 0.01, ValueCheck::positive(), p,
                   bind.member(&P::follower_time));
  return std::make_unique<Hysteresis>(group, p, std::move(bind));
}

std::vector<OutputDeclaration> Hysteresis::outputs() const {
  return {{"stiffness", "N/m", false, false},
          {"offset_force", "N", false, false},
          {"rest_stiffness", "N/m", false, false},
          {"rest_force", "N", false, false},
          {"force", "N"}};
}

void Hysteresis::initialize(const Evaluation& evaluation, std::span<double> own_state) const {
  own_state[0] = input(evaluation, kRestDeflection);
  own_state[1] = 0.0;
}

void Hysteresis::compute_outputs(const Evaluation& evaluation) const {
  const double force = state(evaluation, 1);
  set_output(evaluation, kStiffness, 0.0);
  set_output(evaluation, kOffsetForce, force);
  set_output(evaluation, kRestStiffness, 0.0);
  set_output(evaluation, kRestForce, 0.0);
  set_output(evaluation, kForce, force);
}

void Hysteresis::compute_derivatives(const Evaluation& evaluation, double* derivatives) const {
  const auto& p = run_parameters(evaluation);
  const double rate = hysteresis::follower_rate(p.follower_time, input(evaluation, kDeflection),
                                                state(evaluation, 0));
  set_derivative(derivatives, 0, rate);
  set_derivative(derivatives, 1, hysteresis::force_rate(p, rate, state(evaluation, 1)));
}

}  // namespace tcpmsim
