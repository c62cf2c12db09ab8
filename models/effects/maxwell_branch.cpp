#include "models/effects/maxwell_branch.h"

#include "models/laws/sls.h"
#include "models/typical_values.h"

namespace tcpmsim {

MaxwellBranch::MaxwellBranch(std::string group, MaxwellBranchParameters defaults,
                             ParameterBindings<MaxwellBranchParameters> bindings)
    : ParametricComponent(std::move(group), "maxwell_branch", defaults, std::move(bindings)) {}

std::unique_ptr<MaxwellBranch> MaxwellBranch::from_config(const std::string& group,
                                                          const ConfigNode& node) {
  using P = MaxwellBranchParameters;
  node.declare({"type", "name", "stiffness", "damping", "time_constant"});
  P p;
  ParameterBindings<P> bind;
  // Zero stiffness is allowed: a branch that carries no force (discover's candidates start there,
  // where the augmented model is the base model).
  bind.quantity(node, "stiffness", "N/m", typical::added_stiffness(ValueCheck::non_negative()), p,
                bind.member(&P::stiffness));
  if (node.has("damping") && node.has("time_constant"))
    node.at("time_constant")
        .fail("give damping or time_constant (= damping / stiffness), not both");
  if (node.has("time_constant")) {
    bind.quantity(node, "time_constant", "s", typical::time_constant(ValueCheck::positive()), p,
                  bind.member(&P::time_constant));
  } else {
    bind.quantity(node, "damping", "N*s/m", typical::damping(ValueCheck::positive()), p,
                  bind.member(&P::damping));
  }
  return std::make_unique<MaxwellBranch>(group, p, std::move(bind));
}

std::vector<OutputDeclaration> MaxwellBranch::outputs() const {
  // The affine pair is a port for the SLS only; the force is what the record shows.
  return {{"stiffness", "N/m", false, false},
          {"offset_force", "N", false, false},
          {"rest_stiffness", "N/m", false, false},
          {"rest_force", "N", false, false},
          {"force", "N", true}};
}

void MaxwellBranch::initialize(const Evaluation& evaluation, std::span<double> own_state) const {
  own_state[0] = input(evaluation, kRestDeflection);  // relaxed
}

void MaxwellBranch::compute_outputs(const Evaluation& evaluation) const {
  const auto& p = run_parameters(evaluation);
  set_output(evaluation, kStiffness, p.stiffness);
  set_output(evaluation, kOffsetForce, -p.stiffness * state(evaluation, 0));
  set_output(evaluation, kRestStiffness, 0.0);
  set_output(evaluation, kRestForce, 0.0);
}

void MaxwellBranch::compute_observations(const Evaluation& evaluation) const {
  const auto& p = run_parameters(evaluation);
  set_output(evaluation, kForce,
             sls::arm_force(p.stiffness, input(evaluation, kDeflection), state(evaluation, 0)));
}

void MaxwellBranch::compute_derivatives(const Evaluation& evaluation, double* derivatives) const {
  const auto& p = run_parameters(evaluation);
  set_derivative(derivatives, 0, p.arm_rate(input(evaluation, kDeflection), state(evaluation, 0)));
}

}  // namespace tcpmsim
