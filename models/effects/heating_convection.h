#pragma once

#include <cmath>
#include <memory>

#include "sim/config/config_node.h"
#include "sim/parametric_component.h"

namespace tcpmsim {

// A heat-transfer coefficient that rises while the heating input runs: a heat gun or a fan that
// runs with the heater stirs the air around the muscle, so the loss grows with the input,
//     Q = G_P (P / P_ref) (T - T_amb),
// beside the node's own hA (T - T_amb): at P = P_ref the conductance is hA + G_P, at rest hA.
// A fan switched by the heating (a relay, a thermostat) runs above a power P_on instead:
//     Q = G_P s(P) (T - T_amb),   s(P) = (sigma(P) - sigma(0)) / (1 - sigma(0)),
//     sigma(P) = 1 / (1 + exp(-(P - P_on) / w)),
// a smooth switch of width w (given by switch_power and switch_width, not reference_power),
// off at rest and fully on at high power whatever its width: the logistic sigma alone is not
// off at rest, sigma(0) = 1 / (1 + exp(P_on / w)), 0.7 % at P_on = 5 w but up to 0.47 within
// the widths discover tries (w up to half the peak power, P_on down to a twentieth), a share of
// G_P added to hA whenever the heater is off.
// A flow that spins up and down follows the input late: with a time constant tau the boost is
// driven by the lagged input P_b, tau dP_b/dt = P - P_b (P_b = P at the start; tau = 0: at
// once). With G_P = 0 it takes nothing (discover's nested start).
struct HeatingConvectionParameters {
  double conductance = 0.0;      // G_P [W/K] at the reference power, or switched fully on
  double reference_power = 0.0;  // P_ref [W]; 0 when switched
  double time_constant = 0.0;    // tau [s]; 0: the boost follows the input at once
  double switch_power = 0.0;     // P_on [W]
  double switch_width = 0.0;     // w [W]; 0: proportional to P / P_ref
};

namespace heating_convection {
// The logistic switch sigma(P) = 1 / (1 + exp(-(P - P_on) / w)).
inline double logistic(const HeatingConvectionParameters& p, double power) {
  return 0.5 * (1.0 + std::tanh(0.5 * (power - p.switch_power) / p.switch_width));
}
// s(P): P / P_ref, or the switch (sigma(P) - sigma(0)) / (1 - sigma(0)), 0 at rest.
inline double boost(const HeatingConvectionParameters& p, double power) {
  if (p.switch_width > 0.0) {
    const double at_rest = logistic(p, 0.0);  // below 1/2: P_on >= 0
    return (logistic(p, power) - at_rest) / (1.0 - at_rest);
  }
  return power / p.reference_power;
}
inline double heat_loss(const HeatingConvectionParameters& p, double power, double difference) {
  return p.conductance * boost(p, power) * difference;
}
}  // namespace heating_convection

class HeatingConvection final : public ParametricComponent<HeatingConvectionParameters> {
 public:
  enum Input { kPower, kTemperature, kAmbient };
  enum Output { kHeatLoss };
  HeatingConvection(std::string group, HeatingConvectionParameters defaults,
                    ParameterBindings<HeatingConvectionParameters> bindings = {});
  // Keys conductance, and reference_power or switch_power and switch_width; time_constant
  // (default 0).
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
