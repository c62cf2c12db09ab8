#pragma once

#include <memory>
#include <optional>

#include "sim/config/config_node.h"
#include "sim/parametric_component.h"
#include "sim/signal_reading.h"

namespace tcpmsim {

// One lumped thermal node for the muscle (fibre and heater wire at one temperature):
//   C dT/dt = eta P - hA (T - T_amb) - eps sigma A_r (T^4 - T_amb^4) - sum of attached losses
// The ambient temperature is a prescribed signal (a fan-cooled lab, or a heating chamber's
// staircase as in thesis ch. 6). Further heat-loss laws attach through the fan-in input
// "heat_loss" [W] (models/effects): the node does not know them. Optional energy-accounting
// states integrate the heat in and out, so that  E_in = C (T - T0) + E_out  can be checked.
struct ThermalNodeParameters {
  double heat_capacity = 0.0;       // C [J/K]
  double conductance = 0.0;         // hA [W/K]
  double heating_efficiency = 1.0;  // eta: fraction of the electrical power that heats the node
  double emissivity = 0.0;          // eps; 0 disables radiation
  double radiating_area = 0.0;      // A_r [m^2]
  std::optional<double> initial_temperature;  // [K]; default: the ambient temperature at t0
  bool energy_accounting = false;
};

class ThermalNode final : public ParametricComponent<ThermalNodeParameters> {
 public:
  enum Input { kPower, kHeatLoss };
  enum Output { kTemperature, kAmbientTemperature, kHeatIn, kHeatLost };
  enum State { kTemperatureState, kHeatInState, kHeatLostState };

  ThermalNode(std::string group, ThermalNodeParameters defaults,
              ParameterBindings<ThermalNodeParameters> bindings,
              std::unique_ptr<Signal> ambient_temperature);
  static std::unique_ptr<ThermalNode> from_config(const std::string& group, const ConfigNode& node,
                                                  const SignalContext& signals);

  std::vector<StateDeclaration> states() const override;
  std::vector<OutputDeclaration> outputs() const override;
  std::vector<InputDeclaration> inputs() const override;
  std::vector<SignalDeclaration> signals() const override;
  void initialize(const Evaluation& evaluation, std::span<double> own_state) const override;
  void compute_outputs(const Evaluation& evaluation) const override;
  void compute_derivatives(const Evaluation& evaluation, double* derivatives) const override;
  double next_breakpoint_after(const Evaluation& evaluation) const override;

  // The temperature the node starts from at `start_time`, with the parameters as built.
  double initial_temperature(double start_time) const;
  // Heat leaving the node by its own laws [W] at temperature T and ambient T_amb.
  static double heat_loss(const ThermalNodeParameters& p, double temperature, double ambient);

 private:
  std::unique_ptr<Signal> ambient_;
};

}  // namespace tcpmsim
