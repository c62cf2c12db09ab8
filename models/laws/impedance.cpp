#include "models/laws/impedance.h"

namespace tcpmsim {

double InductanceLaw::operator()(double deflection, double temperature) const {
  return lambda_l / (deflection + lambda_x) + lambda_T * (temperature - reference_temperature) +
         lambda_0;  // (6.3), (7.3)
}

double InductanceLaw::deflection(double inductance, double temperature) const {
  const double shifted = inductance - lambda_0 - lambda_T * (temperature - reference_temperature);
  return (lambda_l - lambda_x * shifted) / shifted;  // (7.4)
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

}  // namespace tcpmsim
