#pragma once

// The drive circuit of (7.2): a supply U_b switching the heater R_m through a series resistance
// R_s, so R_b = R_s + R_m. Shared by the duty-driven JouleDrive and the Muscle Drive.
namespace tcpmsim {

struct PwmSupply {
  double supply_voltage;     // U_b [V]
  double series_resistance;  // R_s [ohm]

  double on_current(double heater_resistance) const;          // U_b / R_b [A]
  double full_power(double heater_resistance) const;          // (7.2) at D = 1 [W]
  double power(double duty, double heater_resistance) const;  // (7.2) P = D^2 R_m (U_b/R_b)^2
};

// The Muscle Drive's inductance measure: switched off, the coil current decays from i_on through
// the heater and the measurement path, L di/dt = -(R_m + R_p) i, and the time it takes to fall
// to the threshold i_th is  t_d = L / (R_m + R_p) ln(i_on / i_th)  [s].
double decay_time(double inductance, double heater_resistance, double path_resistance,
                  double on_current, double threshold_current);

}  // namespace tcpmsim
