#include "models/effects/free_convection.h"

#include <cmath>

#include "models/typical_values.h"

namespace tcpmsim {

FreeConvection::FreeConvection(std::string group, FreeConvectionParameters defaults,
                               ParameterBindings<FreeConvectionParameters> bindings)
    : ParametricComponent(std::move(group), "free_convection", defaults, std::move(bindings)) {}

std::unique_ptr<FreeConvection> FreeConvection::from_config(const std::string& group,
                                                            const ConfigNode& node) {
  using P = FreeConvectionParameters;
  node.declare({"type", "name", "conductance", "reference_difference", "exponent"});
  P p;
  ParameterBindings<P> bind;
  bind.quantity(node, "conductance", "W/K", typical::added_conductance(ValueCheck::non_negative()),
                p, bind.member(&P::conductance));
  bind.quantity(node, "reference_difference", "K", ValueCheck::positive(), p,
                bind.member(&P::reference_difference));
  if (node.has("exponent"))
    bind.quantity(node, "exponent", "1", ValueCheck::between(1.0, 2.0), p,
                  bind.member(&P::exponent));
  return std::make_unique<FreeConvection>(group, p, std::move(bind));
}

double FreeConvection::heat_loss(const FreeConvectionParameters& p, double difference) {
  const double ratio = std::abs(difference) / p.reference_difference;
  if (p.exponent > 0.0)
    return std::copysign(p.conductance * p.reference_difference * std::pow(ratio, p.exponent),
                         difference);
  return std::copysign(p.conductance * p.reference_difference * ratio * std::pow(ratio, 0.25),
                       difference);
}

void FreeConvection::compute_outputs(const Evaluation& evaluation) const {
  set_output(evaluation, kHeatLoss,
             heat_loss(run_parameters(evaluation),
                       input(evaluation, kTemperature) - input(evaluation, kAmbient)));
}

}  // namespace tcpmsim
