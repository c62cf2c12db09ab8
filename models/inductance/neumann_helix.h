#pragma once

#include "models/inductance/coil_geometry.h"

namespace tcpmsim::inductance {

// Neumann's double line integral (2.1) over a helix, after R. Weaver, "The inductance of a helix
// of any pitch" (2011), the algorithm the thesis used (section 2.2.6, ref. [167]).
//
// The wire is a helix of radius r and pitch angle psi, tan psi = l/(2 pi r N), with arc length
// Lw = 2 pi r N / cos psi. Its self-inductance is the mutual inductance of the centre-line
// filament and a second filament displaced by the wire's geometric mean distance g (2.11's
// text) perpendicular to the wire within the winding cylinder: by an angle -theta0 and an axial
// y0 with 2 r^2 (1 - cos theta0) + y0^2 = g^2 and y0 = r theta0 cot psi. With k = cos(psi)/r,
// the integrand depends only on the arc-length difference phi, so the double integral is
//   L = mu0/(4 pi) int_0^Lw (Lw - phi) [F(phi) + F(-phi)] dphi,
//   F(phi) = (1 + cos^2 psi (cos(k phi + theta0) - 1))
//            / sqrt(2 r^2 (1 - cos(k phi + theta0)) + (phi sin psi - y0)^2).
// The integral is split into panels (graded towards phi = 0, where F peaks over a width ~g,
// then a quarter turn each) and each panel is integrated by adaptive Simpson (Weaver uses
// Simpson's rule with interval doubling) until the estimated error is below
// relative_tolerance times the integral of |integrand|.
//
// Because filament 2 is offset axially, turns i and i+1 see each other at p + y0 and p - y0
// rather than p; with the helix's axial current this makes the result exceed Maxwell's ring sum
// (see the README's coil-spring section for the size of both effects).
double neumann_helix_inductance(const CoilGeometry& coil, double relative_tolerance = 1e-9);

}  // namespace tcpmsim::inductance
