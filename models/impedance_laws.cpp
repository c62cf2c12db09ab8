#include "models/impedance_laws.h"

namespace tcpmsim {

double InductanceLaw::operator()(double deflection, double temperature) const {
  return lambda_l / (deflection + lambda_x) + lambda_T * (temperature - reference_temperature) +
         lambda_0;  // (6.3), (7.3)
}

double InductanceLaw::deflection(double inductance, double temperature) const {
  const double shifted = inductance - lambda_0 - lambda_T * (temperature - reference_temperature);
  return (lambda_l - lambda_x * shifted) / shifted;  // (7.4)
}

InductanceLaw InductanceLaw::from_config(const ConfigNode& node) {
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

double ResistanceLaw::operator()(double deflection, double temperature) const {
  return rho_x * deflection + rho_T * (temperature - reference_temperature) + rho_0;  // (6.5)
}

ResistanceLaw ResistanceLaw::thermal(double resistance, double temperature_coefficient,
                                     double reference_temperature, double strain_coefficient) {
  // (6.4): R0 (1 + kappa (T - T0))
  return {strain_coefficient, resistance * temperature_coefficient, resistance,
          reference_temperature};
}

ResistanceLaw ResistanceLaw::from_config(const ConfigNode& node) {
  if (node.is_scalar()) return {0.0, 0.0, node.as_quantity("ohm", ValueCheck::positive()), 273.15};
  node.declare({"form", "rho_x", "rho_T", "rho_0", "reference_temperature", "resistance",
                "temperature_coefficient", "strain_coefficient"});
  const std::string form = node.choice("form", {"linear", "thermal"});
  if (form == "thermal") {
    return thermal(node.quantity("resistance", "ohm", ValueCheck::positive()),
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

double StaticForceLaw::operator()(double deflection, double temperature) const {
  return phi_x * deflection + phi_T * (temperature - reference_temperature) + phi_0;  // (6.9)
}

}  // namespace tcpmsim
