#include "models/effects/nonlinear_stiffness.h"

#include "models/effects/hysteresis.h"
#include "models/typical_values.h"

namespace tcpmsim {

NonlinearStiffness::NonlinearStiffness(std::string group, NonlinearStiffnessParameters defaults,
                                       ParameterBindings<NonlinearStiffnessParameters> bindings)
    : ParametricComponent(std::move(group), "nonlinear_stiffness", defaults, std::move(bindings)) {}

std::unique_ptr<NonlinearStiffness> NonlinearStiffness::from_config(const std::string& group,
                                                                    const ConfigNode& node) {
  using P = NonlinearStiffnessParameters;
  node.declare({"type", "name", "stiffness", "knee_deflection", "knee_width", "follower_time"});
  P p;
  ParameterBindings<P> bind;
  bind.quantity(node, "stiffness", "N/m", {}, p, bind.member(&P::stiffness));
  bind.quantity(node, "knee_deflection", "m", {}, p, bind.member(&P::knee_deflection));
  bind.quantity(node, "knee_width", "m", typical::muscle_length(ValueCheck::positive()), p,
                bind.member(&P::knee_width));
  bind.quantity_or(node, "follower_time", "s", 0.01, ValueCheck::positive(), p,
                   bind.member(&P::follower_time));
  return std::make_unique<NonlinearStiffness>(group, p, std::move(bind));
}

std::vector<OutputDeclaration> NonlinearStiffness::outputs() const {
  return {{"stiffness", "N/m"},
          {"offset_force", "N", false, false},
          {"rest_stiffness", "N/m", false, false},
          {"rest_force", "N", false, false},
          {"force", "N", true}};
}

void NonlinearStiffness::initialize(const Evaluation& evaluation,
                                    std::span<double> own_state) const {
  own_state[0] = input(evaluation, kRestDeflection);
}

void NonlinearStiffness::compute_outputs(const Evaluation& evaluation) const {
  const auto& p = run_parameters(evaluation);
  const double follower = state(evaluation, 0);
  const double s = nonlinear_stiffness::stiffness(p, follower);
  const double offset = nonlinear_stiffness::force(p, follower) - s * follower;
  set_output(evaluation, kStiffness, s);
  set_output(evaluation, kOffsetForce, offset);
  set_output(evaluation, kRestStiffness, s);
  set_output(evaluation, kRestForce, offset);
}

void NonlinearStiffness::compute_observations(const Evaluation& evaluation) const {
  const auto& p = run_parameters(evaluation);
  const double follower = state(evaluation, 0);
  set_output(
      evaluation, kForce,
      nonlinear_stiffness::force(p, follower) + nonlinear_stiffness::stiffness(p, follower) *
                                                    (input(evaluation, kDeflection) - follower));
}

void NonlinearStiffness::compute_derivatives(const Evaluation& evaluation,
                                             double* derivatives) const {
  set_derivative(derivatives, 0,
                 hysteresis::follower_rate(run_parameters(evaluation).follower_time,
                                           input(evaluation, kDeflection), state(evaluation, 0)));
}

}  // namespace tcpmsim
