#pragma once

namespace tcpmsim::inductance {

// Mutual inductance of two coaxial circular filaments of equal radius r at axial distance h,
// Maxwell's formula (2.11)-(2.12), (4.8):
//   M = mu0 r [ (2/k - k) K(k) - (2/k) E(k) ],   k^2 = (2r)^2 / ((2r)^2 + h^2).
// The printed (2.11), -mu0 r ((k - 2/k) K + (2/k) E), is the same expression.
// Limits: M -> mu0 pi r^4 / (2 h^3) for h >> r (two dipoles), M -> mu0 r (ln(8r/h) - 2) for
// h << r. Far-field values do not cancel (a series is used where k^2 < 0.1). Relative accuracy
// about 1e-12 for h >= 0.01 r (bounded by libstdc++'s elliptic integrals, checked against
// 40-digit values), about 1e-10 at h = 1e-3 r (k -> 1 loses digits). h must be positive.
double loop_mutual_inductance(double radius, double distance);

// Geometric mean distance of a round wire's cross-section from itself, g = (delta/2) e^(-1/4)
// (text after (2.12)). With it, loop_mutual_inductance(r, g) is the self-inductance of a ring
// of round wire at low frequency, mu0 r (ln(8r/a) - 7/4) for a = delta/2 << r.
// (4.10) prints delta/4 e^(-1/4); that is a misprint: the round-wire gmd is a e^(-1/4).
double wire_gmd(double wire_diameter);

}  // namespace tcpmsim::inductance
