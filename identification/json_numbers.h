#pragma once

#include <nlohmann/json.hpp>

namespace tcpmsim::fit {

// A number for a JSON report: the value, or null where it is not finite (an unidentified
// parameter's standard error, a score over an empty window), since JSON has no NaN.
nlohmann::json number_or_null(double value);

}  // namespace tcpmsim::fit
