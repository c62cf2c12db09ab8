#include "models/laws/bundle_circuit.h"

#include <cmath>

namespace tcpmsim::bundle_circuit {

OperatingPoint operating_point(SupplyMode mode, double source, double series_resistance,
                               double load) {
  double current = source;
  if (mode == SupplyMode::voltage) current = source / (series_resistance + load);
  if (mode == SupplyMode::power) current = std::sqrt(source / load);
  return {current * load, current};
}

}  // namespace tcpmsim::bundle_circuit
