#include "models/laws/bundle_circuit.h"

#include <cmath>

#include "models/laws/pwm_supply.h"

namespace tcpmsim::bundle_circuit {

OperatingPoint operating_point(SupplyMode mode, double source, double series_resistance,
                               double load) {
  double current = source;
  if (mode == SupplyMode::voltage) current = PwmSupply{source, series_resistance}.on_current(load);
  if (mode == SupplyMode::power) current = std::sqrt(source / load);
  return {current * load, current};
}

}  // namespace tcpmsim::bundle_circuit
