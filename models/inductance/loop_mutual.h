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

// Mutual inductance of two coaxial circular filaments of radii a and b at axial distance h,
// Maxwell's formula in its general form (the equal-radius case is (2.11)):
//   M = mu0 sqrt(a b) [ (2/k - k) K(k) - (2/k) E(k) ],   k^2 = 4 a b / ((a + b)^2 + h^2).
// The bracket comes from the arithmetic-geometric mean (a_0 = 1, b_0 = k', c_0 = k) as
// (K/k) sum_{n>=1} 2^n c_n^2 with K = pi / (2 a_N): a sum of positive terms, so nothing cancels
// far apart (k -> 0), and k'^2 = ((a - b)^2 + h^2) / ((a + b)^2 + h^2) is formed directly, so
// nothing cancels close by (k -> 1). Five or six square roots: a tenth of the cost of
// libstdc++'s K and E, which is what lets a bundle's mutual inductances be computed at load.
// loop_mutual_inductance(r, h) keeps its series/libstdc++ evaluation (the pinned coil records
// were made with it); the two agree to 1e-12 (tests/test_inductance_parallel.cpp).
// std::domain_error unless a, b > 0, h finite, and the rings distinct (not a = b with h = 0).
double coaxial_loops_mutual_inductance(double a, double b, double distance);

// Geometric mean distance of a round wire's cross-section from itself, g = (delta/2) e^(-1/4)
// (text after (2.12)). With it, loop_mutual_inductance(r, g) is the self-inductance of a ring
// of round wire at low frequency, mu0 r (ln(8r/a) - 7/4) for a = delta/2 << r.
// (4.10) prints delta/4 e^(-1/4); that is a misprint: the round-wire gmd is a e^(-1/4).
double wire_gmd(double wire_diameter);

}  // namespace tcpmsim::inductance
