#pragma once

#include <memory>

#include "sim/config/config_node.h"
#include "sim/parametric_component.h"

namespace tcpmsim {

// A share of the heating power that reaches the polymer late: a heater wire, a coating or a
// contact that is heated first passes a share a of the power on through a first-order lag,
//     tau dP_l/dt = P - P_l,     the polymer heated by (1 - a) P + a P_l.
// Attached to the muscle's heat balance, it takes the power not yet passed on,
//     Q = a (P - P_l),
// (in the reduced form (7.1), kappa_P (P - Q)). Over time every joule arrives, so the steady
// state is the single node's; the lag starts in equilibrium with the power at the start
// (P_l = P). With a = 0 it takes nothing and the muscle is the one without it, which is where
// discover's thermal-lag candidates start; a two-node wire (thermal_lag) with a small heat
// capacity behaves like a = 1 with tau = C_w / G_w.
struct HeatingLagParameters {
  double share = 0.0;          // a [1], in [0, 1]
  double time_constant = 0.0;  // tau [s]
};

namespace heating_lag {
// Q = a (P - P_l) [W]: the power still on its way.
inline double held_power(const HeatingLagParameters& p, double power, double lagged_power) {
  return p.share * (power - lagged_power);
}
}  // namespace heating_lag

class HeatingLag final : public ParametricComponent<HeatingLagParameters> {
 public:
  enum Input { kPower };
  enum Output { kHeatLoss, kLaggedPower };
  HeatingLag(std::string group, HeatingLagParameters defaults,
             ParameterBindings<HeatingLagParameters> bindings = {});
  // Keys share, time_constant.
  static std::unique_ptr<HeatingLag> from_config(const std::string& group, const ConfigNode& node);

  std::vector<StateDeclaration> states() const override { return {{"lagged_power", "W", 1e-9}}; }
  std::vector<OutputDeclaration> outputs() const override {
    return {{"heat_loss", "W"}, {"lagged_power", "W"}};
  }
  std::vector<InputDeclaration> inputs() const override { return {{"power", true}}; }
  void initialize(const Evaluation& evaluation, std::span<double> own_state) const override;
  void compute_outputs(const Evaluation& evaluation) const override;
  void compute_derivatives(const Evaluation& evaluation, double* derivatives) const override;
};

}  // namespace tcpmsim
