#pragma once

#include "sim/component.h"

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

class HangingMass final : public Component {
 public:
  enum Input { kMuscleForce };
  enum Output { kDeflection, kVelocity };
  HangingMass(std::string group, HangingMassParameters parameters);

  std::vector<StateDeclaration> states() const override {
    return {{"deflection", "m", 1e-12}, {"velocity", "m/s", 1e-10}};
  }
  std::vector<OutputDeclaration> outputs() const override {
    return {{"deflection", "m"}, {"velocity", "m/s"}};
  }
  std::vector<InputDeclaration> inputs() const override { return {{"force", false}}; }
  void initialize(const Evaluation& evaluation, std::span<double> own_state) const override;
  void compute_outputs(const Evaluation& evaluation) const override;
  void compute_derivatives(const Evaluation& evaluation, double* derivatives) const override;

  const HangingMassParameters& parameters() const { return parameters_; }

 private:
  HangingMassParameters parameters_;
};

}  // namespace tcpmsim
