#pragma once

#include <cmath>
#include <memory>

#include "sim/config/config_node.h"
#include "sim/parametric_component.h"

namespace tcpmsim {

// Rate-independent hysteresis in the muscle's force (Dahl's friction model), attached in
// parallel with the SLS. Its force z follows the deflection x by
//     dz/dt = k_h (v - |v| z / F_h),     v = dx/dt,
// so that on a branch of rising x, z = F_h - (F_h - z0) exp(-k_h (x - x0) / F_h): it depends on
// the path of x, not on its speed, and saturates at +-F_h. The muscle's deflection comes to it
// without its rate, so a follower state u with time constant tau_f (default 10 ms) tracks x,
// du/dt = v = (x - u) / tau_f; the loop is rate-independent for deflections slower than tau_f.
// Its force enters the force balance as an offset (F = z, no stiffness) and it carries none at
// the start (z = 0, u = x).
// Given by its radius r = F_h / k_h instead of F_h, the element is a smoothed stop operator of
// that radius weighted by k_h, dz/dt = k_h v - |v| z / r: its force is linear in k_h (z = k_h s
// with ds/dt = v - |v| s / r, |s| <= r), and k_h = 0 carries none. Several such elements on a
// grid of radii with non-negative weights are a Prandtl-Ishlinskii operator in its stop form,
// of which one Dahl element is the simplest member.
struct HysteresisParameters {
  double stiffness = 0.0;      // k_h [N/m]: the slope of z at a reversal (the weight)
  double force = 0.0;          // F_h [N]: the saturation force; 0 when given by radius
  double radius = 0.0;         // r [m]: the stop operator's radius; 0 when given by force
  double follower_time = 0.0;  // tau_f [s]
};

namespace hysteresis {
// Dahl: dz/dt for a deflection rate v.
inline double force_rate(const HysteresisParameters& p, double rate, double force) {
  if (p.radius > 0.0) return p.stiffness * rate - std::abs(rate) * force / p.radius;
  return p.stiffness * (rate - std::abs(rate) * force / p.force);
}
// The deflection rate the follower gives: (x - u) / tau_f.
inline double follower_rate(double follower_time, double deflection, double follower) {
  return (deflection - follower) / follower_time;
}
}  // namespace hysteresis

class Hysteresis final : public ParametricComponent<HysteresisParameters> {
 public:
  enum Input { kDeflection, kRestDeflection };
  enum Output { kStiffness, kOffsetForce, kRestStiffness, kRestForce, kForce };
  Hysteresis(std::string group, HysteresisParameters defaults,
             ParameterBindings<HysteresisParameters> bindings = {});
  // Keys stiffness, force or radius (one of the two), follower_time (default 10 ms).
  static std::unique_ptr<Hysteresis> from_config(const std::string& group, const ConfigNode& node);

  std::vector<StateDeclaration> states() const override {
    return {{"follower", "m", 1e-12}, {"force", "N", 1e-10}};
  }
  std::vector<OutputDeclaration> outputs() const override;
  std::vector<InputDeclaration> inputs() const override {
    return {{"deflection", false}, {"rest_deflection", false}};
  }
  void initialize(const Evaluation& evaluation, std::span<double> own_state) const override;
  void compute_outputs(const Evaluation& evaluation) const override;
  void compute_derivatives(const Evaluation& evaluation, double* derivatives) const override;
};

}  // namespace tcpmsim
