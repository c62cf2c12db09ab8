#include "models/effects/heating_convection.h"

#include "models/typical_values.h"

namespace tcpmsim {

HeatingConvection::HeatingConvection(std::string group, HeatingConvectionParameters defaults,
                                     ParameterBindings<HeatingConvectionParameters> bindings)
    : ParametricComponent(std::move(group), "heating_convection", defaults, std::move(bindings)) {}

std::unique_ptr<HeatingConvection> HeatingConvection::from_config(const std::string& group,
                                                                  const ConfigNode& node) {
  using P = HeatingConvectionParameters;
  node.declare({"type", "name", "conductance", "reference_power", "time_constant", "switch_power",
                "switch_width"});
  P p;
  ParameterBindings<P> bind;
  bind.quantity(node, "conductance", "W/K", typical::added_conductance(ValueCheck::non_negative()),
                p, bind.member(&P::conductance));
  const bool switched = node.has("switch_power") || node.has("switch_width");
  if (switched && node.has("reference_power"))
    node.at("reference_power")
        .fail(
            "give reference_power (a boost proportional to the power) or switch_power and "
            "switch_width (a switched fan), not both");
  if (switched) {
    bind.quantity(node, "switch_power", "W", ValueCheck::non_negative(), p,
                  bind.member(&P::switch_power));
    bind.quantity(node, "switch_width", "W", ValueCheck::positive(), p,
                  bind.member(&P::switch_width));
  } else {
    bind.quantity(node, "reference_power", "W", ValueCheck::positive(), p,
                  bind.member(&P::reference_power));
  }
  bind.quantity_or(node, "time_constant", "s", 0.0, ValueCheck::non_negative(), p,
                   bind.member(&P::time_constant));
  return std::make_unique<HeatingConvection>(group, p, std::move(bind));
}

void HeatingConvection::initialize(const Evaluation& evaluation,
                                   std::span<double> own_state) const {
  own_state[0] = input(evaluation, kPower);
}

void HeatingConvection::compute_outputs(const Evaluation& evaluation) const {
  const auto& p = run_parameters(evaluation);
  const double drive = p.time_constant > 0.0 ? state(evaluation, 0) : input(evaluation, kPower);
  set_output(evaluation, kHeatLoss,
             heating_convection::heat_loss(
                 p, drive, input(evaluation, kTemperature) - input(evaluation, kAmbient)));
}

void HeatingConvection::compute_derivatives(const Evaluation& evaluation,
                                            double* derivatives) const {
  const auto& p = run_parameters(evaluation);
  set_derivative(derivatives, 0,
                 p.time_constant > 0.0
                     ? (input(evaluation, kPower) - state(evaluation, 0)) / p.time_constant
                     : 0.0);
}

}  // namespace tcpmsim
