#include "identification/json_numbers.h"

#include <cmath>

namespace tcpmsim::fit {

nlohmann::json number_or_null(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

}  // namespace tcpmsim::fit
