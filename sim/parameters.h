#pragma once

#include <functional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "sim/value_check.h"

namespace tcpmsim {

// A number of an assembled model that a run may change without rebuilding it: addressed by its
// path, the instance name followed by the key path in the scenario file
// ("muscle.mechanics.k2", "left.thermal.heat_capacity", "drive.power.values[1]"), in SI.
struct ParameterDeclaration {
  std::string path;
  std::string unit;  // the SI unit of `value`, spelled as a scenario states it ("N/m", "1")
  double value = 0.0;
  ValueCheck check;
  // A condition beyond the range: returns the problem ("expected a non-zero value"), or "".
  std::function<std::string(double)> extra_check;
};

// A parameter value a run cannot take: out of range, derived from others, or an unknown path.
class ParameterError : public std::invalid_argument {
 public:
  ParameterError(const std::string& path, const std::string& problem);
};

// "" if `value` suits `declaration`, else what was expected ("expected a positive value in N/m,
// got -1 N/m").
std::string parameter_problem(const ParameterDeclaration& declaration, double value);

}  // namespace tcpmsim
