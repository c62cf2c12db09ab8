#pragma once

#include <limits>

namespace tcpmsim {

// The value of a result that could not be computed (a metric without the samples it needs, an
// unidentified estimate): quiet NaN, written to files as such and to JSON as null.
inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace tcpmsim
