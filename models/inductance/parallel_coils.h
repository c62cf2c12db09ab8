#pragma once

#include "models/inductance/coil_geometry.h"

namespace tcpmsim::inductance {

// Mutual inductance of two circular filaments with parallel axes (Neumann's formula (2.1) for
// two rings): radii a and b, the second ring's centre displaced by `lateral` across the axes
// and `axial` along them,
//   M = mu0 a b / (4 pi) int_0^2pi int_0^2pi cos(t1 - t2) / R(t1, t2) dt1 dt2,
//   R^2 = (a cos t1 - lateral - b cos t2)^2 + (a sin t1 - b sin t2)^2 + axial^2.
// The inner integral is done in closed form: it is the first ring's vector potential, which
// at distance rho from its axis is M_coax(a, rho, axial) / (2 pi rho) (Maxwell's formula,
// coaxial_loops_mutual_inductance). The single integral left along the second ring is smooth
// and periodic while the rings do not meet, so the trapezoidal rule converges geometrically;
// the intervals are doubled until two estimates agree to 1e-12 of the integral of the
// integrand's magnitude (side by side M is a small difference of large parts);
// std::domain_error if 65536 intervals over half a turn do not (rings a few 1e-9 r apart).
// Coaxial rings (lateral 0) give Maxwell's (2.11); side by side (axial 0, lateral >> a, b) two
// coplanar dipoles, M -> -mu0 pi a^2 b^2 / (4 lateral^3): negative, a neighbour's flux returns
// through the ring. std::domain_error if the rings meet.
double parallel_loops_mutual_inductance(double a, double b, double lateral, double axial);

// Two equal single-layer coils side by side, axes parallel `separation` apart and ends level,
// each a stack of round(N) rings at the pitch p = l / N as in Maxwell's summation (2.13):
//   M = sum_{i,j} M_rings(separation, (i - j) p) = sum_{|s| < n} (n - |s|) M_rings(sep, s p).
// Side by side means separation > 2 r (the wire centres' circles apart); std::domain_error
// otherwise.
double parallel_coils_mutual_inductance(const CoilGeometry& coil, double separation);

}  // namespace tcpmsim::inductance
