#include "models/laws/impedance.h"

#include <cmath>
#include <limits>

namespace tcpmsim {

double InductanceLaw::operator()(double deflection, double temperature) const {
  return lambda_l / (deflection + lambda_x) + lambda_T * (temperature - reference_temperature) +
         lambda_0;  // (6.3), (7.3)
}

double InductanceLaw::deflection(double inductance, double temperature) const {
  const double shifted = inductance - lambda_0 - lambda_T * (temperature - reference_temperature);
  return (lambda_l - lambda_x * shifted) / shifted;  // (7.4)
}

double InductanceLaw::coupled_deflection(double inductance, double temperature,
                                         const std::function<double(double)>& coupling) const {
  constexpr int kMostIterations = 50;
  constexpr double kAgreement = 1e-15;  // [m]
  constexpr double kUnknown = std::numeric_limits<double>::quiet_NaN();
  const double floor = lambda_T * (temperature - reference_temperature);
  double deflection = this->deflection(inductance, temperature);
  for (int k = 0; k < kMostIterations; ++k) {
    const double own = inductance - coupling(deflection);
    if (!(own - lambda_0 - floor > 0.0)) return kUnknown;
    const double next = this->deflection(own, temperature);
    if (std::abs(next - deflection) <= kAgreement) return next;
    deflection = next;
  }
  return kUnknown;
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
