#pragma once

#include "models/inductance/coil_geometry.h"

namespace tcpmsim::inductance {

// Current-sheet solenoid formulas (thesis section 2.2.2-2.2.3).

// (2.2) L = mu0 N^2 pi r^2 / l: an infinitely long sheet, cut to length l.
double basic_solenoid_inductance(const CoilGeometry& coil);

// Nagaoka's coefficient (2.4)-(2.6) as a function of u = 2r/l (diameter over length):
//   kappa = 4/(3 pi k') [ (k'^2/k^2)(K(k) - E(k)) + E(k) - k ],
//   k^2 = u^2/(1 + u^2) = (2r)^2/((2r)^2 + l^2),  k'^2 = 1 - k^2 = l^2/((2r)^2 + l^2).
// (The printed (2.5)/(2.6) lack the square on l in the denominators.) kappa(0) = 1;
// kappa(1) = 0.68842. K and E take the modulus k.
double nagaoka_coefficient(double diameter_over_length);

// (2.3) L = kappa(2r/l) mu0 N^2 pi r^2 / l: the uniform current sheet of finite length.
double nagaoka_inductance(const CoilGeometry& coil);

}  // namespace tcpmsim::inductance
