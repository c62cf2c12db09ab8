#pragma once

#include <memory>

#include "models/laws/sls.h"
#include "sim/config/config_node.h"
#include "sim/parametric_component.h"

namespace tcpmsim {

// The muscle's mechanics as a component: the SLS of (7.5)-(7.6) (models/laws/sls.h) with the
// dashpot extension x_d as its state.
//
// Causality follows what the muscle is attached to, found when the system is assembled: with
// its "deflection" input connected (an imposed deflection, a mass) x is an input and F an
// output; with its "force" input connected (an imposed force) F is the input and x follows
// algebraically from (7.5). With its "cable_deflection" input connected (a joint that pulls
// through a cable or tendon) the deflection is imposed as long as the muscle is taut, but a
// cable cannot push: where the imposed deflection would put the muscle in compression (F < 0),
// the muscle goes slack at its force-free deflection instead, longer than the cable's path
// (the cable goes loose),
//     x = max(x_cable, x_free),   F(x_free) = 0 (deflection_at_force with F = 0),
// so F = max(F(x_cable), 0) (F rises with x: k1 + k2 + S > 0); a slack muscle's force is 0. Exactly
// one of the three must be connected.
//
// Further force terms attach without the SLS knowing them (models/effects). Each publishes its
// force as affine in the deflection at its present state, F_j = s_j x + b_j, through the
// fan-in inputs "attached_stiffness" (s_j) and "attached_force" (b_j), so that (7.5) becomes
//     F = F_l + F_T + phi_0 + S x + B,   S = sum s_j, B = sum b_j,
// and stays solvable for x under an imposed force; and the same pair at rest (every internal
// dashpot relaxed) through "attached_rest_stiffness" and "attached_rest_force": a Maxwell arm
// carries nothing at rest, a parallel spring its stiffness. The muscle starts at rest, at the
// port-only output "rest_deflection": x itself when x is imposed, and under an imposed force
// (F - F_T - phi_0 - B_rest) / (k1 + S_rest); the attached terms start at rest there too.
class SlsMechanics final : public ParametricComponent<SlsParameters> {
 public:
  enum Input {
    kThermalForce,
    kDeflection,
    kForce,
    kAttachedStiffness,
    kAttachedForce,
    kAttachedRestStiffness,
    kAttachedRestForce,
    kCableDeflection
  };
  // Besides the recorded force, deflection and elastic force, port-only outputs: the rest
  // deflection (above), and the small-signal stiffness dF/dx the muscle presents to what holds
  // it, 0 while slack: "stiffness" at its present state (k1 + k2 + S: the instantaneous,
  // elastic response) and "rest_stiffness" once its dashpots have relaxed (k1 + S_rest; 0 if it
  // would then be slack).
  enum Output {
    kForceOutput,
    kDeflectionOutput,
    kElasticForce,
    kRestDeflection,
    kStiffness,
    kRestStiffness
  };

  SlsMechanics(std::string group, SlsParameters defaults,
               ParameterBindings<SlsParameters> bindings = {});
  // Keys k1, k2, damping, force_offset.
  static std::unique_ptr<SlsMechanics> from_config(const std::string& group,
                                                   const ConfigNode& node);
  // The same keys, for a model of the muscle elsewhere (the estimator's).
  static SlsParameters read(const ConfigNode& node, ParameterBindings<SlsParameters>* bindings);

  std::vector<StateDeclaration> states() const override {
    return {{"dashpot_extension", "m", 1e-12}};
  }
  std::vector<OutputDeclaration> outputs() const override;
  std::vector<InputDeclaration> inputs() const override;
  std::string check_connections() const override;
  void initialize(const Evaluation& evaluation, std::span<double> own_state) const override;
  void compute_outputs(const Evaluation& evaluation) const override;
  void compute_derivatives(const Evaluation& evaluation, double* derivatives) const override;
  Dependencies derivative_dependencies(int state_index) const override;

  // Whether the deflection is imposed (known once assembled).
  bool deflection_imposed() const { return source_count(kDeflection) > 0; }
  // Whether it is held through a cable that cannot push (known once assembled).
  bool held_by_cable() const { return source_count(kCableDeflection) > 0; }

 private:
  double deflection(const Evaluation& evaluation) const;
  double rest_deflection(const Evaluation& evaluation) const;
  double free_deflection(const Evaluation& evaluation) const;
  bool has_attachments() const { return source_count(kAttachedStiffness) > 0; }
};

}  // namespace tcpmsim
