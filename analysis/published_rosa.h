#pragma once

#include "models/inductance/coil_geometry.h"

namespace tcpmsim::analysis {

// The Rosa column of thesis Tables 2.2 and 2.3 as the published analysis computed it: NOT a
// physical model, a reproduction of a defect, kept to show where the published numbers come
// from.
//
// The published MATLAB (evlasblom/coil-spring-inductance, inductance_functions/L_rosa_w.m,
// called by processing_function.m) takes Nagaoka's coefficient from a transcription of
// Weaver's arithmetic-geometric-mean routine whose do-while loop became
//     co = c; while c < co ... end
// The condition is false on entry, so the AGM never iterates: K = pi/2 (its value at k = 0)
// and E = K (1 - (c^2/2 + k^2)/2) with c = 1 - k'. With these K and E in (2.4), and Weaver's
// closed-form B, (2.7)-(2.10) give exactly the published Rosa R^2 and RMSE (all 8 sequences,
// to the printed digits); the correct coefficient gives the physical Rosa column instead.
double published_rosa_inductance(const inductance::CoilGeometry& coil);

// The defective Nagaoka coefficient used inside it, as a function of 2r/l.
double published_rosa_nagaoka_coefficient(double diameter_over_length);

}  // namespace tcpmsim::analysis
