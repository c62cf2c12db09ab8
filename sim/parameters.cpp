#include "sim/parameters.h"

#include <cmath>
#include <sstream>

namespace tcpmsim {

ParameterError::ParameterError(const std::string& path, const std::string& problem)
    : std::invalid_argument(path.empty() ? problem : path + ": " + problem),
      path_(path),
      problem_(problem) {}

std::string parameter_problem(const ParameterDeclaration& declaration, double value) {
  std::ostringstream text;
  text << value;
  if (declaration.unit != "1") text << " " << declaration.unit;
  if (!std::isfinite(value)) return "expected a finite value, got " + text.str();
  if (!declaration.check.accepts(value))
    return "expected " + declaration.check.expectation(declaration.unit) + ", got " + text.str();
  if (declaration.extra_check) return declaration.extra_check(value);
  return {};
}

}  // namespace tcpmsim
