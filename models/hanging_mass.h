#pragma once

#include <functional>
#include <memory>

#include "sim/config/config_node.h"
#include "sim/parametric_component.h"

namespace tcpmsim {

// A mass hanging from the muscle under gravity, with optional viscous damping:
//     dx/dt = v,   m dv/dt = m g - F_muscle - b v,
// where x is the muscle's deflection (elongation) and F_muscle its tension.
struct HangingMassParameters {
  double mass = 0.0;                // [kg]
  double gravity = 9.80665;         // [m/s^2] (standard gravity)
  double damping = 0.0;             // b [N s/m]
  double initial_deflection = 0.0;  // [m]
  double initial_velocity = 0.0;    // [m/s]
};

class HangingMass final : public ParametricComponent<HangingMassParameters> {
 public:
  enum Input { kMuscleForce };
  enum Output { kDeflection, kVelocity };
  HangingMass(std::string group, HangingMassParameters defaults,
              ParameterBindings<HangingMassParameters> bindings);
  // Keys mass, gravity, damping, initial_deflection (a quantity, or `equilibrium`: then
  // `equilibrium` gives it from the weight m g), and initial_velocity.
  static std::unique_ptr<HangingMass> from_config(
      const std::string& group, const ConfigNode& node,
      const std::function<double(double weight)>& equilibrium);

  std::vector<StateDeclaration> states() const override {
    return {{"deflection", "m", 1e-12}, {"velocity", "m/s", 1e-10}};
  }
  std::vector<OutputDeclaration> outputs() const override {
    return {{"deflection", "m"}, {"velocity", "m/s"}};
  }
  std::vector<InputDeclaration> inputs() const override {
    return {{"force", false, false, InputArity::many}};
  }
  void initialize(const Evaluation& evaluation, std::span<double> own_state) const override;
  void compute_outputs(const Evaluation& evaluation) const override;
  void compute_derivatives(const Evaluation& evaluation, double* derivatives) const override;
};

}  // namespace tcpmsim
