#include "models/laws/thermal_force.h"

#include <cmath>
#include <stdexcept>

namespace tcpmsim {

ReducedThermalForceParameters thermal_force::reduce(double heat_capacity, double conductance,
                                                    double force_per_kelvin,
                                                    double ambient_temperature) {
  ReducedThermalForceParameters p;
  p.heating_gain = force_per_kelvin / heat_capacity;  // kappa_P = phi_T / C
  p.cooling_rate = conductance / heat_capacity;       // kappa_c = hA / C
  p.ambient_temperature = ambient_temperature;
  p.force_per_kelvin = force_per_kelvin;
  return p;
}

DiscreteThermalForce::DiscreteThermalForce(double heating_gain, double cooling_rate, double period)
    : decay_(std::exp(-cooling_rate * period)),
      // (kappa_P / kappa_c)(1 - exp(-kappa_c T)), with expm1 so that slow cooling keeps its
      // digits (the limit kappa_c -> 0 is kappa_P T).
      gain_(cooling_rate > 0.0 ? -heating_gain / cooling_rate * std::expm1(-cooling_rate * period)
                               : heating_gain * period) {
  if (!(cooling_rate >= 0.0)) throw std::invalid_argument("thermal force: kappa_c must be >= 0");
}

}  // namespace tcpmsim
