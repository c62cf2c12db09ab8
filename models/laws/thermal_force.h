#pragma once

#include <optional>

// The thermal contribution to the muscle force, F_T in (7.5), in two forms.
//
// Physical form: F_T = phi_T (T - T_ref), with T from a thermal node.
//
// Reduced form (7.1): dF_T/dt = kappa_P P - kappa_c F_T, the thesis' identified model. It is
// the physical form with a linear thermal node C dT/dt = P - hA (T - T_amb) and
// T_ref = T_amb, rewritten in F_T:
//     kappa_c = hA / C,   kappa_P = phi_T / C   (and F_T = phi_T (T - T_amb)).
// Only the ratios are identifiable; given phi_T the reduced form can still report
// T = T_amb + F_T / phi_T.
//
// One law, one place: the plant components (models/thermal_force.h), the estimator's exact
// discretisation (DiscreteThermalForce) and the describing-function analysis use these.
namespace tcpmsim {

struct ReducedThermalForceParameters {
  double heating_gain = 0.0;               // kappa_P [N/J]
  double cooling_rate = 0.0;               // kappa_c [1/s]
  double ambient_temperature = 0.0;        // [K], for the reported temperature
  std::optional<double> force_per_kelvin;  // phi_T [N/K], enables the temperature output
  double initial_thermal_force = 0.0;      // F_T(t0) [N]
};

namespace thermal_force {

// (7.1): dF_T/dt = kappa_P P - kappa_c F_T
inline double rate(double heating_gain, double cooling_rate, double thermal_force, double power) {
  return heating_gain * power - cooling_rate * thermal_force;
}

// F_T = phi_T (T - T_ref)
inline double physical(double force_per_kelvin, double temperature, double reference_temperature) {
  return force_per_kelvin * (temperature - reference_temperature);
}

// The reduced form's reported temperature, T = T_amb + F_T / phi_T.
inline double temperature(double ambient_temperature, double thermal_force,
                          double force_per_kelvin) {
  return ambient_temperature + thermal_force / force_per_kelvin;
}

// The steady state of (7.1): the power that holds F_T, P* = (kappa_c / kappa_P) F_T.
inline double equilibrium_power(double heating_gain, double cooling_rate, double thermal_force) {
  return cooling_rate / heating_gain * thermal_force;
}

// The mapping between the forms, documented above.
ReducedThermalForceParameters reduce(double heat_capacity, double conductance,
                                     double force_per_kelvin, double ambient_temperature);

}  // namespace thermal_force

// (7.1) discretised exactly for a power held constant over each sample interval (the Muscle
// Drive holds its duty cycle for a whole PWM period). Integrating dF_T/dt = kappa_P P - kappa_c F_T
// over one period T with P constant:
//     F_T[k] = phi F_T[k-1] + gamma P[k-1],   phi = exp(-kappa_c T),
//     gamma = (kappa_P / kappa_c) (1 - phi),
// where P[k-1] is the power applied over [t_{k-1}, t_k). The estimator reads the controller's
// held command at t_k, which is exactly that power.
class DiscreteThermalForce {
 public:
  DiscreteThermalForce(double heating_gain, double cooling_rate, double period);
  void reset(double thermal_force) { value_ = thermal_force; }
  double advance(double power) { return value_ = decay_ * value_ + gain_ * power; }
  double value() const { return value_; }
  double decay() const { return decay_; }  // phi
  double gain() const { return gain_; }    // gamma [N/W]

 private:
  double decay_;
  double gain_;
  double value_ = 0.0;
};

}  // namespace tcpmsim
