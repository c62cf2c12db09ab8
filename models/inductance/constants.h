#pragma once

#include <numbers>

namespace tcpmsim::inductance {

// Magnetic constant as the thesis uses it (ch. 2, ch. 4): mu0 = 4 pi 1e-7 H/m exactly.
// Since the 2019 SI revision mu0 is measured, 1.25663706212(19)e-6 H/m, i.e. 4 pi 1e-7 times
// (1 + 5.5e-10); the difference is far below every tolerance in this library.
inline constexpr double mu0 = 4e-7 * std::numbers::pi;  // [H/m]

}  // namespace tcpmsim::inductance
