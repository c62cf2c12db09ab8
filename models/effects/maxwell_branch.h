#pragma once

#include <memory>

#include "models/laws/sls.h"
#include "sim/config/config_node.h"
#include "sim/parametric_component.h"

namespace tcpmsim {

// A further viscoelastic branch attached to a muscle: a spring k_b in series with a dashpot
// c_b (a Maxwell element) in parallel with the SLS, which makes the muscle a generalized
// Maxwell (Wiechert) solid with one more relaxation time, c_b / k_b. With the dashpot
// extension y as state,
//     c_b dy/dt = k_b (x - y),    F_b = k_b (x - y),
// so a deflection step dx relaxes as k_b dx exp(-t k_b / c_b) beside the SLS's own
// k2 dx exp(-t k2 / c). It publishes its force as affine in the deflection at its present
// state, F_b = s x + b with s = k_b and b = -k_b y (the muscle's "attached_stiffness" and
// "attached_force" ports), so that the SLS can solve (7.5) for x under an imposed force; nothing
// at rest (the relaxed arm carries no force); and F_b itself (observed) for the record. It
// starts relaxed, y = x at the muscle's rest.
// The branch is given by k_b and c_b, or by k_b and its relaxation time tau_b = c_b / k_b (which
// keeps the time scale a parameter of its own while k_b is varied, as discover's candidates do).
struct MaxwellBranchParameters {
  double stiffness = 0.0;      // k_b [N/m]
  double damping = 0.0;        // c_b [N s/m]; 0 when given by time_constant
  double time_constant = 0.0;  // tau_b [s]; 0 when given by damping
  double dashpot() const { return time_constant > 0.0 ? stiffness * time_constant : damping; }
  // dy/dt = k_b (x - y) / c_b; a branch without stiffness (it carries no force) relaxes its arm
  // at its time constant, or not at all when given by its damping.
  double arm_rate(double deflection, double extension) const {
    if (stiffness > 0.0) return sls::arm_rate(stiffness, dashpot(), deflection, extension);
    return time_constant > 0.0 ? (deflection - extension) / time_constant : 0.0;
  }
};

class MaxwellBranch final : public ParametricComponent<MaxwellBranchParameters> {
 public:
  enum Input { kDeflection, kRestDeflection };
  enum Output { kStiffness, kOffsetForce, kRestStiffness, kRestForce, kForce };
  MaxwellBranch(std::string group, MaxwellBranchParameters defaults,
                ParameterBindings<MaxwellBranchParameters> bindings = {});
  // Keys stiffness, and damping or time_constant (one of the two).
  static std::unique_ptr<MaxwellBranch> from_config(const std::string& group,
                                                    const ConfigNode& node);

  std::vector<StateDeclaration> states() const override {
    return {{"dashpot_extension", "m", 1e-12}};
  }
  std::vector<OutputDeclaration> outputs() const override;
  // Read for the derivative and the record, and once to start from; neither with feedthrough.
  std::vector<InputDeclaration> inputs() const override {
    return {{"deflection", false}, {"rest_deflection", false}};
  }
  void initialize(const Evaluation& evaluation, std::span<double> own_state) const override;
  void compute_outputs(const Evaluation& evaluation) const override;
  void compute_observations(const Evaluation& evaluation) const override;
  void compute_derivatives(const Evaluation& evaluation, double* derivatives) const override;
};

}  // namespace tcpmsim
