#include "models/effects/free_convection.h"

#include <cmath>

namespace tcpmsim {

FreeConvection::FreeConvection(std::string group, FreeConvectionParameters defaults,
                               ParameterBindings<FreeConvectionParameters> bindings)
    : ParametricComponent(std::move(group), "free_convection", defaults, std::move(bindings)) {}

std::unique_ptr<FreeConvection> FreeConvection::from_config(const std::string& group,
                                                            const ConfigNode& node) {
  using P = FreeConvectionParameters;
  node.declare({"type", "name", "conductance", "reference_difference"});
  P p;
  ParameterBindings<P> bind;
  bind.quantity(node, "conductance", "W/K", ValueCheck::non_negative(), p,
                bind.member(&P::conductance));
  bind.quantity(node, "reference_difference", "K", ValueCheck::positive(), p,
                bind.member(&P::reference_difference));
  return std::make_unique<FreeConvection>(group, p, std::move(bind));
}

double FreeConvection::heat_loss(const FreeConvectionParameters& p, double difference) {
  const double ratio = std::abs(difference) / p.reference_difference;
  return std::copysign(p.conductance * p.reference_difference * ratio * std::pow(ratio, 0.25),
                       difference);
}

void FreeConvection::compute_outputs(const Evaluation& evaluation) const {
  set_output(evaluation, kHeatLoss,
             heat_loss(run_parameters(evaluation),
                       input(evaluation, kTemperature) - input(evaluation, kAmbient)));
}

}  // namespace tcpmsim
