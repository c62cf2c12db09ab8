#pragma once

#include <memory>

#include "sim/config/config_node.h"
#include "sim/parametric_component.h"

namespace tcpmsim {

// The heater wire and the polymer as two thermal nodes. The power heats the wire (heat capacity
// C_w), which passes it on to the polymer through the conductance G_w:
//     C_w dT_w/dt = P - G_w (T_w - T).
// Attached to the muscle's heat balance, it takes the power not yet passed on,
//     Q = P - G_w (T_w - T),
// so the polymer is heated by G_w (T_w - T) instead of P: a lag of about C_w / G_w between the
// power and the polymer's heating that a single node cannot show. In the reduced form (7.1)
// the same Q is taken from the power, kappa_P (P - Q). The wire starts in equilibrium with the
// power at the start, T_w = T + P / G_w, and the steady state is the single node's.
struct ThermalLagParameters {
  double heat_capacity = 0.0;  // C_w [J/K]
  double conductance = 0.0;    // G_w [W/K]
};

namespace thermal_lag {
// Q = P - G_w (T_w - T) [W]: the power still in the wire.
inline double held_power(const ThermalLagParameters& p, double power, double wire_temperature,
                         double temperature) {
  return power - p.conductance * (wire_temperature - temperature);
}
}  // namespace thermal_lag

class ThermalLag final : public ParametricComponent<ThermalLagParameters> {
 public:
  enum Input { kPower, kTemperature };
  enum Output { kHeatLoss, kWireTemperature };
  ThermalLag(std::string group, ThermalLagParameters defaults,
             ParameterBindings<ThermalLagParameters> bindings = {});
  // Keys heat_capacity, conductance.
  static std::unique_ptr<ThermalLag> from_config(const std::string& group, const ConfigNode& node);

  std::vector<StateDeclaration> states() const override {
    return {{"wire_temperature", "K", 1e-6}};
  }
  std::vector<OutputDeclaration> outputs() const override {
    return {{"heat_loss", "W"}, {"wire_temperature", "K"}};
  }
  std::vector<InputDeclaration> inputs() const override {
    return {{"power", true}, {"temperature", true}};
  }
  void initialize(const Evaluation& evaluation, std::span<double> own_state) const override;
  void compute_outputs(const Evaluation& evaluation) const override;
  void compute_derivatives(const Evaluation& evaluation, double* derivatives) const override;
};

}  // namespace tcpmsim
