#pragma once

#include <memory>

#include "sim/config/config_node.h"
#include "sim/parametric_component.h"

namespace tcpmsim {

// A body beside the polymer that stores heat: a clamp, a holder, a mandrel or a coating the
// muscle touches. The polymer heats it through the conductance G_s, and it warms with the time
// constant tau_s = C_s / G_s of its own heat capacity C_s,
//     tau_s dT_s/dt = T - T_s,     Q = G_s (T - T_s).
// Attached to the muscle's heat balance, Q is what the polymer loses to it: more while the
// polymer warms, none once the body has caught up, heat given back while the polymer cools. So
// the steady state is the single node's and the transients are slower, in heating and in
// cooling; a second node after the polymer, where thermal_lag and heating_lag are one before it.
// The body starts at the polymer's temperature. With G_s = 0 it takes nothing and the muscle is
// the one without it: where discover's thermal-lag candidates start.
struct HeatSinkParameters {
  double conductance = 0.0;    // G_s [W/K]
  double time_constant = 0.0;  // tau_s = C_s / G_s [s]; 0 when given by heat_capacity
  double heat_capacity = 0.0;  // C_s [J/K]; 0 when given by time_constant
};

namespace heat_sink {
// Q = G_s (T - T_s) [W]: the heat flowing from the polymer into the body.
inline double heat_loss(const HeatSinkParameters& p, double temperature, double sink_temperature) {
  return p.conductance * (temperature - sink_temperature);
}
// dT_s/dt [K/s]: (T - T_s) / tau_s, or Q / C_s when given by its heat capacity.
inline double warming(const HeatSinkParameters& p, double temperature, double sink_temperature) {
  if (p.time_constant > 0.0) return (temperature - sink_temperature) / p.time_constant;
  return heat_loss(p, temperature, sink_temperature) / p.heat_capacity;
}
}  // namespace heat_sink

class HeatSink final : public ParametricComponent<HeatSinkParameters> {
 public:
  enum Input { kTemperature };
  enum Output { kHeatLoss, kSinkTemperature };
  HeatSink(std::string group, HeatSinkParameters defaults,
           ParameterBindings<HeatSinkParameters> bindings = {});
  // Keys conductance, and time_constant or heat_capacity (C_s = G_s tau_s).
  static std::unique_ptr<HeatSink> from_config(const std::string& group, const ConfigNode& node);

  std::vector<StateDeclaration> states() const override {
    return {{"sink_temperature", "K", 1e-6}};
  }
  std::vector<OutputDeclaration> outputs() const override {
    return {{"heat_loss", "W"}, {"sink_temperature", "K"}};
  }
  std::vector<InputDeclaration> inputs() const override { return {{"temperature", true}}; }
  void initialize(const Evaluation& evaluation, std::span<double> own_state) const override;
  void compute_outputs(const Evaluation& evaluation) const override;
  void compute_derivatives(const Evaluation& evaluation, double* derivatives) const override;
};

}  // namespace tcpmsim
