// Neumann's integral over a helix (2.1) after Weaver (2011): limits, convergence, tolerance.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <vector>

#include "models/inductance/constants.h"
#include "models/inductance/loop_mutual.h"
#include "models/inductance/maxwell.h"
#include "models/inductance/neumann_helix.h"

using namespace tcpmsim::inductance;

TEST_CASE("One helical turn of vanishing pitch has the self-inductance of a ring of wire") {
  // Textbook ring of round wire (Rosa & Grover 1912): mu0 r (ln(8r/a) - 7/4) for a << r. An open
  // turn differs from the closed ring near its gap; the difference is of order pitch/radius.
  const double r = 10e-3, a = 0.25e-3;
  const double ring = mu0 * r * (std::log(8.0 * r / a) - 1.75);
  for (double pitch : {1e-4, 1e-5, 1e-6}) {
    const double helix = neumann_helix_inductance({r, pitch, 1.0, 2.0 * a}, 1e-10);
    INFO("pitch = " << pitch);
    CHECK(std::abs(helix - ring) / ring <= pitch / r + 4.0 * (a / r) * (a / r));
    // ... and to Maxwell's self term M(g) itself, to which the gap is the only difference.
    const double self = loop_mutual_inductance(r, wire_gmd(2.0 * a));
    CHECK(std::abs(helix - self) / self <= pitch / r);
  }
}

TEST_CASE("A helix tends to Maxwell's stack of rings as its pitch vanishes") {
  // Ten turns on r = 10 mm; the pitch shrinks 4x per step and the wire as pitch^2, so that the
  // pitch angle psi, the gmd-to-pitch ratio g/p and p/r all vanish. What separates a helix from
  // rings -- its axial current (~sin^2 psi), the offset filament's asymmetric view of the
  // neighbouring turns (~(g/p)^2) and the wire's open ends (~p/r) -- vanishes with them.
  const double r = 10e-3;
  std::vector<double> differences;
  for (double scale : {1.0, 0.25, 0.0625, 0.015625}) {
    const double pitch = 2e-3 * scale, wire = 0.5e-3 * scale * scale;
    const CoilGeometry coil{r, 10 * pitch, 10.0, wire};
    const double helix = neumann_helix_inductance(coil, 1e-10);
    const double rings = maxwell_inductance(coil);
    differences.push_back(std::abs(helix - rings) / rings);
  }
  INFO("relative differences " << differences[0] << " " << differences[1] << " " << differences[2]
                               << " " << differences[3]);
  for (std::size_t i = 1; i < differences.size(); ++i) CHECK(differences[i] < differences[i - 1]);
  CHECK(differences.back() < differences.front() / 100.0);
  CHECK(differences.back() <= 2e-3 * 0.015625 / r);  // below p/r of the last step
}

TEST_CASE("The helix integral meets the requested relative tolerance") {
  // Spring S1 of thesis Table 2.1 stretched 5 %: each result within its tolerance of a result
  // computed 1000 times tighter.
  const CoilGeometry s1{8.47e-3, 1.05 * 118.17e-3, 118.17 / 2.82, 2.82e-3};
  const double reference = neumann_helix_inductance(s1, 1e-13);
  for (double tolerance : {1e-3, 1e-5, 1e-7, 1e-9, 1e-10}) {
    INFO("tolerance " << tolerance);
    CHECK(std::abs(neumann_helix_inductance(s1, tolerance) - reference) / reference <= tolerance);
  }
}

TEST_CASE("The helix exceeds the ring stack by its axial current and offset filament") {
  // For S1 at 5 % stretch the helix gives 4 % more than Maxwell's rings. Two estimates account
  // for it: the axial current I sin(psi) along the coil, a straight conductor of length l on the
  // radius r, (mu0 l / 2 pi)(ln(2l/r) - 1) for l >> r; and the second filament's axial offset
  // y0 ~ g, which puts turn pairs at m p + g and m p - g instead of m p:
  // sum_m (N - m) [M(m p + g) + M(m p - g) - 2 M(m p)]. Both are leading-order estimates (the
  // first neglects terms of order r/l = 0.07, the second the offset's angular part).
  const double r = 8.47e-3, delta = 2.82e-3, lc = 118.17e-3, n = lc / delta;
  const CoilGeometry s1{r, 1.05 * lc, n, delta};
  const double difference = neumann_helix_inductance(s1, 1e-10) - maxwell_inductance(s1);
  const double l = s1.length, p = s1.pitch(), g = wire_gmd(delta);
  const double axial = mu0 * l / (2.0 * std::numbers::pi) * (std::log(2.0 * l / r) - 1.0);
  double offset = 0.0;
  const int rings = static_cast<int>(std::lround(n));
  for (int m = 1; m < rings; ++m) {
    offset +=
        (rings - m) * (loop_mutual_inductance(r, m * p + g) + loop_mutual_inductance(r, m * p - g) -
                       2.0 * loop_mutual_inductance(r, m * p));
  }
  CHECK(difference > 0.03 * maxwell_inductance(s1));
  CHECK(std::abs(difference - (axial + offset)) <= 0.1 * difference);
}
