#include "models/static_self_sensing.h"

#include <cmath>

namespace tcpmsim {

DeflectionAndTemperature invert_impedance(const InductanceLaw& inductance,
                                          const ResistanceLaw& resistance, double measured_L,
                                          double measured_R) {
  if (resistance.rho_T == 0.0) {
    throw OutsideModelRange("temperature is not observable from resistance when rho_T = 0");
  }
  const double lambda_0 =
      inductance.lambda_0 +
      inductance.lambda_T * (resistance.reference_temperature - inductance.reference_temperature);
  const double b = resistance.rho_T * (measured_L - lambda_0) -
                   inductance.lambda_T *
                       (measured_R - resistance.rho_0 + resistance.rho_x * inductance.lambda_x);
  const double discriminant = b * b + 4.0 * inductance.lambda_T * resistance.rho_x *
                                          resistance.rho_T * inductance.lambda_l;  // (6.8)
  if (!(discriminant >= 0.0) || !(b + std::sqrt(discriminant) > 0.0)) {
    throw OutsideModelRange("(L, R) has no physical solution for (x, T) under this model");
  }
  const double u = 2.0 * resistance.rho_T * inductance.lambda_l / (b + std::sqrt(discriminant));
  const double deflection = u - inductance.lambda_x;  // (6.7)
  const double temperature =
      resistance.reference_temperature +
      (measured_R - resistance.rho_0 - resistance.rho_x * deflection) / resistance.rho_T;  // (6.6)
  return {deflection, temperature};
}

}  // namespace tcpmsim
