#include "models/laws/pwm_supply.h"

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

}  // namespace tcpmsim
