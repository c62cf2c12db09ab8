#pragma once

#include <memory>

#include "sim/config/config_node.h"
#include "sim/parametric_component.h"

namespace tcpmsim {

// A heat-transfer coefficient that rises while the heating input runs: a heat gun or a fan that
// runs with the heater stirs the air around the muscle, so the loss grows with the input,
//     Q = G_P (P / P_ref) (T - T_amb),
// beside the node's own hA (T - T_amb): at P = P_ref the conductance is hA + G_P, at rest hA.
// A flow that spins up and down follows the input late: with a time constant tau the boost is
// driven by the lagged input P_b, tau dP_b/dt = P - P_b (P_b = P at the start; tau = 0: at
// once). With G_P = 0 it takes nothing (discover's nested start).
struct HeatingConvectionParameters {
  double conductance = 0.0;      // G_P [W/K] at the reference power
  double reference_power = 0.0;  // P_ref [W]
  double time_constant = 0.0;    // tau [s]; 0: the boost follows the input at once
};

namespace heating_convection {
inline double heat_loss(const HeatingConvectionParameters& p, double power, double difference) {
  return p.conductance * (power / p.reference_power) * difference;
}
}  // namespace heating_convection

class HeatingConvection final : public ParametricComponent<HeatingConvectionParameters> {
 public:
  enum Input { kPower, kTemperature, kAmbient };
  enum Output { kHeatLoss };
  HeatingConvection(std::string group, HeatingConvectionParameters defaults,
                    ParameterBindings<HeatingConvectionParameters> bindings = {});
  // Keys conductance, reference_power, time_constant (default 0).
  static std::unique_ptr<HeatingConvection> from_config(const std::string& group,
                                                        const ConfigNode& node);

  std::vector<StateDeclaration> states() const override { return {{"boost_power", "W", 1e-9}}; }
  std::vector<OutputDeclaration> outputs() const override { return {{"heat_loss", "W"}}; }
  std::vector<InputDeclaration> inputs() const override {
    return {{"power", true}, {"temperature", true}, {"ambient_temperature", true}};
  }
  void initialize(const Evaluation& evaluation, std::span<double> own_state) const override;
  void compute_outputs(const Evaluation& evaluation) const override;
  void compute_derivatives(const Evaluation& evaluation, double* derivatives) const override;
};

}  // namespace tcpmsim
