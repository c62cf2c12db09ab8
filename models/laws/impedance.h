#pragma once

#include <functional>

// The heater coil's impedance laws (thesis ch. 6-7): small value types with no dependence on
// components or configuration. The plant's CoilImpedance, the estimator's inversion (7.4) and
// the static self-sensing of (6.6)-(6.8) use them.
namespace tcpmsim {

// Fitted inductance of a TCPM's heater coil (thesis (6.3); (7.3) with lambda_x for l0):
//     L(x, T) = lambda_l / (x + lambda_x) + lambda_T (T - T_ref) + lambda_0.
// The thesis uses T in degC, i.e. T_ref = 273.15 K. With `measure` units the law gives the
// Muscle Drive's inductance measure L* (decay time, proportional to inductance) instead of
// henries: lambda_l in m, lambda_0 dimensionless.
struct InductanceLaw {
  double lambda_l = 0.0;
  double lambda_x = 0.0;  // [m]
  double lambda_T = 0.0;  // per K
  double lambda_0 = 0.0;
  double reference_temperature = 273.15;  // [K]
  bool is_measure = false;                // L* (dimensionless) rather than H

  double operator()(double deflection, double temperature) const;
  // Inverse at a known temperature; at lambda_T = 0 this is (7.4).
  double deflection(double inductance, double temperature) const;
  // The inverse of law(x, T) + coupling(x), a neighbour's mutual inductance on top of the coil's
  // own: by fixed-point iteration from the uncoupled inverse (the coupling changes with x far
  // less than the law). NaN where inductance - coupling leaves the inverse's domain (at or
  // below lambda_0 + lambda_T (T - T_ref)) or no fixed point is found.
  double coupled_deflection(double inductance, double temperature,
                            const std::function<double(double)>& coupling) const;
};

// Heater resistance (6.5):  R(x, T) = rho_x x + rho_T (T - T_ref) + rho_0.
// The physical form (6.4), R = R0 (1 + kappa (T - T0)), is rho_T = R0 kappa, rho_0 = R0,
// T_ref = T0, with rho_x the strain sensitivity (0 if unknown).
struct ResistanceLaw {
  double rho_x = 0.0;                     // [ohm/m]
  double rho_T = 0.0;                     // [ohm/K]
  double rho_0 = 0.0;                     // [ohm]
  double reference_temperature = 273.15;  // [K]

  double operator()(double deflection, double temperature) const;
  static ResistanceLaw thermal(double resistance, double temperature_coefficient,
                               double reference_temperature, double strain_coefficient = 0.0);
};

}  // namespace tcpmsim
