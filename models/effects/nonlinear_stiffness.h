#pragma once

#include <cmath>
#include <memory>

#include "sim/config/config_node.h"
#include "sim/parametric_component.h"

namespace tcpmsim {

// A stiffness that depends on the deflection: a spring in parallel with the SLS that engages
// past a knee (coils coming into contact, the "preload knee"). Its force is a smoothed hinge,
//     F_n(x) = k_n w softplus((x - x_k) / w),   softplus(z) = ln(1 + e^z),
// whose stiffness dF_n/dx = k_n / (1 + exp(-(x - x_k) / w)) rises from 0 below the knee x_k to
// k_n above it over a width w; k_n < 0 makes it a softening past the knee. The muscle's
// deflection reaches it without feedthrough (the SLS solves the force balance with the
// stiffness it publishes), so it is linearised about a follower state u that tracks x with the
// time constant tau_f (default 10 ms): F = F_n(u) + F_n'(u) (x - u), exact to O((x - u)^2). It
// carries its force at rest as well (it has no dashpot).
struct NonlinearStiffnessParameters {
  double stiffness = 0.0;        // k_n [N/m], above the knee
  double knee_deflection = 0.0;  // x_k [m]
  double knee_width = 0.0;       // w [m]
  double follower_time = 0.0;    // tau_f [s]
};

namespace nonlinear_stiffness {
// F_n(x) [N].
inline double force(const NonlinearStiffnessParameters& p, double deflection) {
  const double z = (deflection - p.knee_deflection) / p.knee_width;
  const double softplus = z > 0.0 ? z + std::log1p(std::exp(-z)) : std::log1p(std::exp(z));
  return p.stiffness * p.knee_width * softplus;
}
// dF_n/dx [N/m].
inline double stiffness(const NonlinearStiffnessParameters& p, double deflection) {
  const double z = (deflection - p.knee_deflection) / p.knee_width;
  return p.stiffness / (1.0 + std::exp(-z));
}
}  // namespace nonlinear_stiffness

class NonlinearStiffness final : public ParametricComponent<NonlinearStiffnessParameters> {
 public:
  enum Input { kDeflection, kRestDeflection };
  enum Output { kStiffness, kOffsetForce, kRestStiffness, kRestForce, kForce };
  NonlinearStiffness(std::string group, NonlinearStiffnessParameters defaults,
                     ParameterBindings<NonlinearStiffnessParameters> bindings = {});
  // Keys stiffness, knee_deflection, knee_width, follower_time (default 10 ms).
  static std::unique_ptr<NonlinearStiffness> from_config(const std::string& group,
                                                         const ConfigNode& node);

  std::vector<StateDeclaration> states() const override { return {{"follower", "m", 1e-12}}; }
  std::vector<OutputDeclaration> outputs() const override;
  std::vector<InputDeclaration> inputs() const override {
    return {{"deflection", false}, {"rest_deflection", false}};
  }
  void initialize(const Evaluation& evaluation, std::span<double> own_state) const override;
  void compute_outputs(const Evaluation& evaluation) const override;
  void compute_observations(const Evaluation& evaluation) const override;
  void compute_derivatives(const Evaluation& evaluation, double* derivatives) const override;
};

}  // namespace tcpmsim
