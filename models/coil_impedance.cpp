#include "models/coil_impedance.h"

namespace tcpmsim {

InductanceLaw read_inductance_law(const ConfigNode& node) {
  node.declare(
      {"quantity", "lambda_l", "lambda_x", "lambda_T", "lambda_0", "reference_temperature"});
  InductanceLaw law;
  law.is_measure = node.choice_or("quantity", {"inductance", "measure"}, "inductance") == "measure";
  const char* per_length = law.is_measure ? "m" : "H*m";
  const char* value = law.is_measure ? "1" : "H";
  const char* per_kelvin = law.is_measure ? "1/K" : "H/K";
  law.lambda_l = node.quantity("lambda_l", per_length, ValueCheck::positive());
  law.lambda_x = node.quantity("lambda_x", "m", ValueCheck::positive());
  law.lambda_0 = node.quantity("lambda_0", value);
  law.lambda_T = node.quantity_or("lambda_T", per_kelvin, 0.0);
  if (law.lambda_T != 0.0) {
    law.reference_temperature = node.quantity("reference_temperature", "K", ValueCheck::positive());
  }
  return law;
}

ResistanceLaw read_resistance_law(const ConfigNode& node) {
  if (node.is_scalar()) return {0.0, 0.0, node.as_quantity("ohm", ValueCheck::positive()), 273.15};
  node.declare({"form", "rho_x", "rho_T", "rho_0", "reference_temperature", "resistance",
                "temperature_coefficient", "strain_coefficient"});
  const std::string form = node.choice("form", {"linear", "thermal"});
  if (form == "thermal") {
    return ResistanceLaw::thermal(
        node.quantity("resistance", "ohm", ValueCheck::positive()),
        node.quantity("temperature_coefficient", "1/K"),
        node.quantity("reference_temperature", "K", ValueCheck::positive()),
        node.quantity_or("strain_coefficient", "ohm/m", 0.0));
  }
  ResistanceLaw law;
  law.rho_x = node.quantity("rho_x", "ohm/m");
  law.rho_T = node.quantity("rho_T", "ohm/K");
  law.rho_0 = node.quantity("rho_0", "ohm");
  law.reference_temperature = node.quantity("reference_temperature", "K", ValueCheck::positive());
  return law;
}

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
