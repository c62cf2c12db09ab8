#include "models/effects/thermal_lag.h"

#include "models/typical_values.h"

namespace tcpmsim {

ThermalLag::ThermalLag(std::string group, ThermalLagParameters defaults,
                       ParameterBindings<ThermalLagParameters> bindings)
    : ParametricComponent(std::move(group), "thermal_lag", defaults, std::move(bindings)) {}

std::unique_ptr<ThermalLag> ThermalLag::from_config(const std::string& group,
                                                    const ConfigNode& node) {
  using P = ThermalLagParameters;
  node.declare({"type", "name", "heat_capacity", "conductance"});
  P p;
  ParameterBindings<P> bind;
  bind.quantity(node, "heat_capacity", "J/K", typical::heat_capacity(ValueCheck::positive()), p,
                bind.member(&P::heat_capacity));
  bind.quantity(node, "conductance", "W/K", typical::conductance(ValueCheck::positive()), p,
                bind.member(&P::conductance));
  return std::make_unique<ThermalLag>(group, p, std::move(bind));
}

void ThermalLag::initialize(const Evaluation& evaluation, std::span<double> own_state) const {
  own_state[0] = input(evaluation, kTemperature) +
                 input(evaluation, kPower) / run_parameters(evaluation).conductance;
}

void ThermalLag::compute_outputs(const Evaluation& evaluation) const {
  const double wire = state(evaluation, 0);
  set_output(evaluation, kHeatLoss,
             thermal_lag::held_power(run_parameters(evaluation), input(evaluation, kPower), wire,
                                     input(evaluation, kTemperature)));
  set_output(evaluation, kWireTemperature, wire);
}

void ThermalLag::compute_derivatives(const Evaluation& evaluation, double* derivatives) const {
  const auto& p = run_parameters(evaluation);
  set_derivative(derivatives, 0,
                 thermal_lag::held_power(p, input(evaluation, kPower), state(evaluation, 0),
                                         input(evaluation, kTemperature)) /
                     p.heat_capacity);
}

}  // namespace tcpmsim
