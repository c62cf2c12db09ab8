#pragma once

#include <span>

#include "models/inductance/coil_geometry.h"

namespace tcpmsim::inductance {

// Maxwell's summation (thesis section 2.2.5 and (4.11)): a coil as coaxial rings of radius r,
// every pair contributing the loop mutual inductance M(h_ij) of (2.11), each ring with itself
// M(g) at the wire's geometric mean distance g.

// (2.13) for `rings` equally spaced rings, corrected (the printed 2(N-1) M_{1,i} must be the
// sum over distances):  L = n M(g) + sum_{i=1}^{n-1} 2 (n - i) M(i p).
double maxwell_ring_stack(double radius, double self_distance, int rings, double pitch);

// (2.13) for a coil whose N may be non-integer, as in the thesis' analysis (physics.md):
// the self term N M(g), the mutual terms of round(N) rings at the pitch p = l/N.
double maxwell_inductance(const CoilGeometry& coil);

// (4.11) for arbitrary ring positions xi (any order, distinct):
//   L = sum_i sum_j M(h_ij), h_ij = |xi_i - xi_j|, h_ii = self_distance.
// Direct O(N^2) evaluation of the elliptic integrals; MaxwellEvaluator does the same fast.
double maxwell_positions(double radius, double self_distance, std::span<const double> positions);

}  // namespace tcpmsim::inductance
