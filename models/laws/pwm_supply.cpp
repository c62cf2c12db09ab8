#include "models/laws/pwm_supply.h"

#include <cmath>

namespace tcpmsim {

double PwmSupply::on_current(double heater_resistance) const {
  return supply_voltage / (series_resistance + heater_resistance);
}

double PwmSupply::full_power(double heater_resistance) const {
  const double current = on_current(heater_resistance);
  return heater_resistance * current * current;
}

double PwmSupply::power(double duty, double heater_resistance) const {
  return duty * duty * full_power(heater_resistance);  // (7.2)
}

double decay_time(double inductance, double heater_resistance, double path_resistance,
                  double on_current, double threshold_current) {
  return inductance / (heater_resistance + path_resistance) *
         std::log(on_current / threshold_current);
}

}  // namespace tcpmsim
