#pragma once

#include <stdexcept>

#include "models/laws/impedance.h"

namespace tcpmsim {

struct DeflectionAndTemperature {
  double deflection;   // [m]
  double temperature;  // [K]
};

class OutsideModelRange : public std::domain_error {
 public:
  using std::domain_error::domain_error;
};

// Static self-sensing (thesis (6.6)-(6.8), re-derived): recovers (x, T) from a measured
// inductance L and resistance R.
//
// Eliminating T with (6.5), tau = T - T_ref,R = (R - rho_0 - rho_x x) / rho_T, and writing
// u = x + lambda_x in (6.3) gives the quadratic
//     a u^2 + b u + c = 0,  a = lambda_T rho_x,
//     b = rho_T (L - lambda_0') - lambda_T (R - rho_0 + rho_x lambda_x),  c = -rho_T lambda_l,
// with lambda_0' = lambda_0 + lambda_T (T_ref,R - T_ref,L). The physical root is the one that
// tends to lambda_l / (L - lambda_0) as the temperature coupling vanishes:
//     u = 2 rho_T lambda_l / (b + sqrt(b^2 + 4 lambda_T rho_x rho_T lambda_l)),
// written in this form because it does not cancel when lambda_T rho_x -> 0. It equals the
// thesis' (6.7) with +sqrt(D); the printed (6.6) for T has +sqrt(D) too, which pairs T with the
// other root: T needs -sqrt(D) in that form.
DeflectionAndTemperature invert_impedance(const InductanceLaw& inductance,
                                          const ResistanceLaw& resistance, double measured_L,
                                          double measured_R);

}  // namespace tcpmsim
