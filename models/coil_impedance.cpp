#include "models/coil_impedance.h"

namespace tcpmsim {

CoilImpedance::CoilImpedance(std::string group, InductanceLaw inductance, ResistanceLaw resistance)
    : Component(std::move(group), "coil_impedance"),
      inductance_(inductance),
      resistance_(resistance) {}

bool CoilImpedance::needs_temperature() const {
  return inductance_.lambda_T != 0.0 || resistance_.rho_T != 0.0;
}

std::vector<OutputDeclaration> CoilImpedance::outputs() const {
  return {inductance_.is_measure ? OutputDeclaration{"inductance_measure", "1"}
                                 : OutputDeclaration{"inductance", "H"},
          {"resistance", "ohm"}};
}

std::vector<InputDeclaration> CoilImpedance::inputs() const {
  if (needs_temperature()) return {{"deflection", true}, {"temperature", true}};
  return {{"deflection", true}};
}

void CoilImpedance::compute_outputs(const Evaluation& evaluation) const {
  const double deflection = input(evaluation, 0);
  const double temperature = needs_temperature() ? input(evaluation, 1) : 0.0;
  set_output(evaluation, kInductance, inductance_(deflection, temperature));
  set_output(evaluation, kResistance, resistance_(deflection, temperature));
}

}  // namespace tcpmsim
