#pragma once

#include <memory>

#include "sim/config/config_node.h"
#include "sim/parametric_component.h"

namespace tcpmsim {

// A temperature-dependent spring in parallel with the SLS: the part of a polymer muscle's
// stiffness that softens as it is heated (above its glass transition a polymer's modulus
// falls steeply). Its stiffness is linear in the muscle's temperature, floored at zero, plus an
// optional unfloored slope:
//     s(T) = max(0, s_ref (1 + alpha (T - T_ref))) + beta dT + gamma dT^2,  dT = T - T_ref,
//     F_s = s(T) x,
// with alpha < 0 for softening. The slope beta [N/(m K)] and curvature gamma [N/(m K^2)] (keys
// stiffness_slope, stiffness_curvature, 0 unless given) change the muscle's own stiffness with
// temperature, softening from any stiffness: a spring of zero size cannot soften, so these are
// the forms discover frees from zero (a transition's bend needs the curvature). It carries the same
// force at rest (it has no dashpot), so it publishes s as both its present and its rest stiffness
// and no offset force (the muscle's "attached_*" ports). Heating the muscle therefore lowers what
// it presents to a joint, r^2 (k1 + s(T)), which is why co-contraction (heating both muscles of a
// pair) softens a joint of such muscles instead of stiffening it.
struct ThermalSofteningParameters {
  double reference_stiffness = 0.0;    // s_ref [N/m]
  double temperature_coefficient = 0;  // alpha [1/K]
  double reference_temperature = 0.0;  // T_ref [K]
  double stiffness_slope = 0.0;        // beta [N/(m K)]
  double stiffness_curvature = 0.0;    // gamma [N/(m K^2)]
};

namespace thermal_softening {
inline double stiffness(const ThermalSofteningParameters& p, double temperature) {
  const double rise = temperature - p.reference_temperature;
  const double s = p.reference_stiffness * (1.0 + p.temperature_coefficient * rise);
  const double floored = s > 0.0 ? s : 0.0;
  if (p.stiffness_slope == 0.0 && p.stiffness_curvature == 0.0) return floored;
  return floored + (p.stiffness_slope + p.stiffness_curvature * rise) * rise;
}
}  // namespace thermal_softening

class ThermalSoftening final : public ParametricComponent<ThermalSofteningParameters> {
 public:
  enum Input { kTemperature, kDeflection };
  enum Output { kStiffness, kOffsetForce, kRestStiffness, kRestForce, kForce };
  ThermalSoftening(std::string group, ThermalSofteningParameters defaults,
                   ParameterBindings<ThermalSofteningParameters> bindings);
  // Keys reference_stiffness, temperature_coefficient, reference_temperature, and optionally
  // stiffness_slope and stiffness_curvature (parameters only when given).
  static std::unique_ptr<ThermalSoftening> from_config(const std::string& group,
                                                       const ConfigNode& node);

  std::vector<OutputDeclaration> outputs() const override;
  // The temperature sets the stiffness (feedthrough); the deflection only the recorded force.
  std::vector<InputDeclaration> inputs() const override {
    return {{"temperature", true}, {"deflection", false}};
  }
  void compute_outputs(const Evaluation& evaluation) const override;
  void compute_observations(const Evaluation& evaluation) const override;
};

}  // namespace tcpmsim
