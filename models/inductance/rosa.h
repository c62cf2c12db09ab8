#pragma once

#include "models/inductance/coil_geometry.h"

namespace tcpmsim::inductance {

// Rosa's round-wire correction to Nagaoka's current sheet (thesis section 2.2.4):
//   (2.7) L = L_Nagaoka - Delta L,   (2.8) Delta L = mu0 r N (A + B).
// A corrects the self-inductance of each turn (round wire versus a strip of width p), B the
// mutual inductance of the turns (rings versus sheet). Both are natural logarithms.

// (2.9) A = 5/4 - ln(2 p / delta) with the pitch p = l/N.
double rosa_self_correction(double pitch, double wire_diameter);

// (2.10) B = (2/N) sum_{i=1}^{N-1} (N - i) sum_{j>=1} (1/(2j) + 1/(2j+2) - 2/(2j+1)) i^(-2j),
// summed to rounding. The inner sum at i = 1 converges like 1/j^2; it is the closed form
// 3/2 - 2 ln 2 there. For non-integer N the outer sum runs over every i < N with weight
// (N - i), which is continuous in N (the published MATLAB loops over 1:N-1, i.e. i <= N-1).
// Grover's table (Inductance Calculations, 1946, p. 150): B(2) = 0.1137, B(10) = 0.2664.
double rosa_mutual_correction_series(double turns);

// Weaver's closed form of B (R. Weaver, "Numerical methods for inductance calculation", 2012,
// as in physics.md): B = ln 2pi - 3/2 - ln N/(6N) - 0.33084236/N - 1/(120 N^3) + 1/(504 N^5)
//                       - 0.0011923/N^7 + 0.0005068/N^9.
double rosa_mutual_correction_weaver(double turns);

enum class RosaMutualCorrection { series, weaver };

// (2.7)-(2.10): Nagaoka's inductance minus Rosa's correction.
double rosa_inductance(const CoilGeometry& coil,
                       RosaMutualCorrection method = RosaMutualCorrection::weaver);

}  // namespace tcpmsim::inductance
