#include "models/effects/thermal_softening.h"

#include "models/typical_values.h"

namespace tcpmsim {

ThermalSoftening::ThermalSoftening(std::string group, ThermalSofteningParameters defaults,
                                   ParameterBindings<ThermalSofteningParameters> bindings)
    : ParametricComponent(std::move(group), "thermal_softening", defaults, std::move(bindings)) {}

std::unique_ptr<ThermalSoftening> ThermalSoftening::from_config(const std::string& group,
                                                                const ConfigNode& node) {
  using P = ThermalSofteningParameters;
  node.declare({"type", "name", "reference_stiffness", "temperature_coefficient",
                "reference_temperature", "stiffness_slope", "stiffness_curvature"});
  P p;
  ParameterBindings<P> bind;
  bind.quantity(node, "reference_stiffness", "N/m",
                typical::added_stiffness(ValueCheck::non_negative()), p,
                bind.member(&P::reference_stiffness));
  bind.quantity(node, "temperature_coefficient", "1/K", {}, p,
                bind.member(&P::temperature_coefficient));
  bind.quantity(node, "reference_temperature", "K", typical::temperature(ValueCheck::positive()), p,
                bind.member(&P::reference_temperature));
  if (node.has("stiffness_slope"))
    bind.quantity(node, "stiffness_slope", "N/(m*K)", {}, p, bind.member(&P::stiffness_slope));
  if (node.has("stiffness_curvature")) {
    bind.quantity(node, "stiffness_curvature", "N/(m*K^2)", {}, p,
                  bind.member(&P::stiffness_curvature));
  }
  return std::make_unique<ThermalSoftening>(group, p, std::move(bind));
}

std::vector<OutputDeclaration> ThermalSoftening::outputs() const {
  return {{"stiffness", "N/m"},
          {"offset_force", "N", false, false},
          {"rest_stiffness", "N/m", false, false},
          {"rest_force", "N", false, false},
          {"force", "N", true}};
}

void ThermalSoftening::compute_outputs(const Evaluation& evaluation) const {
  const double s =
      thermal_softening::stiffness(run_parameters(evaluation), input(evaluation, kTemperature));
  set_output(evaluation, kStiffness, s);
  set_output(evaluation, kOffsetForce, 0.0);
  set_output(evaluation, kRestStiffness, s);
  set_output(evaluation, kRestForce, 0.0);
}

void ThermalSoftening::compute_observations(const Evaluation& evaluation) const {
  const double s =
      thermal_softening::stiffness(run_parameters(evaluation), input(evaluation, kTemperature));
  set_output(evaluation, kForce, s * input(evaluation, kDeflection));
}

}  // namespace tcpmsim
