#include "sim/parameters.h"

namespace tcpmsim {

ParameterError::ParameterError(const std::string& path, const std::string& problem)
    : std::invalid_argument(path.empty() ? problem : path + ": " + problem) {}

std::string parameter_problem(const ParameterDeclaration& declaration, double value) {
  const std::string shown =
      number_text(value) + (declaration.unit == "1" ? "" : " " + declaration.unit);
  if (std::string problem = declaration.check.problem(value, declaration.unit, shown);
      !problem.empty())
    return problem;
  if (declaration.extra_check) return declaration.extra_check(value);
  return {};
}

}  // namespace tcpmsim
