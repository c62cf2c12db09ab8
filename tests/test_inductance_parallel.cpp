// Mutual inductance of rings and coils with parallel axes (issue 10, magnetic coupling in a
// bundle), against Maxwell's closed form for coaxial rings and the dipole limit.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "models/inductance/constants.h"
#include "models/inductance/loop_mutual.h"
#include "models/inductance/parallel_coils.h"

using namespace tcpmsim::inductance;

TEST_CASE("Coaxial rings give Maxwell's elliptic-integral formula (2.11)") {
  const double r = 0.8e-3;
  for (double h : {0.05e-3, 0.3e-3, 1.6e-3, 10e-3}) {
    INFO("h = " << h);
    CHECK(parallel_loops_mutual_inductance(r, r, 0.0, h) ==
          Approx(loop_mutual_inductance(r, h)).epsilon(1e-10));
  }
}

TEST_CASE("Far apart side by side, two rings are coplanar dipoles: M = -mu0 pi a^2 b^2 / 4 d^3") {
  const double a = 1e-3, b = 0.5e-3;
  for (double d : {50e-3, 200e-3}) {
    const double dipoles = -mu0 * std::numbers::pi * a * a * b * b / (4.0 * d * d * d);
    // The next term is relatively (a^2 + b^2) / d^2 smaller.
    CHECK(parallel_loops_mutual_inductance(a, b, d, 0.0) ==
          Approx(dipoles).epsilon(3.0 * (a * a + b * b) / (d * d)));
  }
  // Along the axis at the same distance the dipoles are aligned: twice as large, positive.
  const double d = 200e-3;
  CHECK(parallel_loops_mutual_inductance(a, b, 0.0, d) ==
        Approx(mu0 * std::numbers::pi * a * a * b * b / (2.0 * d * d * d)).epsilon(1e-4));
  // In between, (3 cos^2 theta - 1) / 2 of that: at 45 degrees a quarter of the axial value.
  const double offset = d / std::sqrt(2.0);
  CHECK(parallel_loops_mutual_inductance(a, b, offset, offset) ==
        Approx(mu0 * std::numbers::pi * a * a * b * b * 0.5 / (4.0 * d * d * d)).epsilon(1e-4));
}

TEST_CASE("The mutual inductance of two rings is symmetric in the rings and in the offset") {
  const double a = 0.7e-3, b = 0.9e-3, d = 1.3e-3, c = 0.4e-3;
  const double m = parallel_loops_mutual_inductance(a, b, d, c);
  CHECK(parallel_loops_mutual_inductance(b, a, d, c) == Approx(m).epsilon(1e-12));
  CHECK(parallel_loops_mutual_inductance(a, b, d, -c) == Approx(m).epsilon(1e-12));
}

TEST_CASE("Rings that meet and coils that overlap are refused") {
  CHECK_THROWS_AS(parallel_loops_mutual_inductance(1e-3, 1e-3, 1.5e-3, 0.0), std::domain_error);
  CHECK_THROWS_AS(parallel_loops_mutual_inductance(1e-3, 1e-3, 0.0, 0.0), std::domain_error);
  CHECK_NOTHROW(parallel_loops_mutual_inductance(1e-3, 0.4e-3, 0.5e-3, 0.0));  // one inside
  const CoilGeometry coil{0.7e-3, 20e-3, 20.0, 0.2e-3};
  CHECK_THROWS_AS(parallel_coils_mutual_inductance(coil, 1.4e-3), std::domain_error);
  // All but touching (a gap of 1e-6 r): the rule cannot converge and says so.
  CHECK_THROWS_WITH(parallel_loops_mutual_inductance(0.7e-3, 0.7e-3, 1.4000007e-3, 0.0),
                    Catch::Contains("no convergence"));
}

TEST_CASE("Two coils side by side sum every pair of rings, one of each") {
  const CoilGeometry coil{0.7e-3, 12e-3, 12.0, 0.2e-3};
  const double separation = 1.6e-3;
  double pairs = 0.0;
  for (int i = 0; i < 12; ++i)
    for (int j = 0; j < 12; ++j)
      pairs += parallel_loops_mutual_inductance(coil.radius, coil.radius, separation,
                                                (i - j) * coil.pitch());
  const double mutual = parallel_coils_mutual_inductance(coil, separation);
  CHECK(mutual == Approx(pairs).epsilon(1e-12));
  // Side by side the coils oppose each other's flux, and the coupling is weak against the
  // coils' own inductance (Maxwell's sum for the same coil is a few hundred nH).
  CHECK(mutual < 0.0);
}
