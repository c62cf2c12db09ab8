#include "models/effects/heating_convection.h"

namespace tcpmsim {

HeatingConvection::HeatingConvection(std::string group, HeatingConvectionParameters defaults,
                                     ParameterBindings<HeatingConvectionParameters> bindings)
    : ParametricComponent(std::move(group), "heating_convection", defaults, std::move(bindings)) {}

std::unique_ptr<HeatingConvection> HeatingConvection::from_config(const std::string& group,
                                                                  const ConfigNode& node) {
  using P = HeatingConvectionParameters;
  node.declare({"type", "name", "conductance", "reference_power"});
  P p;
  ParameterBindings<P> bind;
  bind.quantity(node, "conductance", "W/K", ValueCheck::non_negative(), p,
                bind.member(&P::conductance));
  bind.quantity(node, "reference_power", "W", ValueCheck::positive(), p,
                bind.member(&P::reference_power));
  return std::make_unique<HeatingConvection>(group, p, std::move(bind));
}

void HeatingConvection::compute_outputs(const Evaluation& evaluation) const {
  set_output(
      evaluation, kHeatLoss,
      heating_convection::heat_loss(run_parameters(evaluation), input(evaluation, kPower),
                                    input(evaluation, kTemperature) - input(evaluation, kAmbient)));
}

}  // namespace tcpmsim
