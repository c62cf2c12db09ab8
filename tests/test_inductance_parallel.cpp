// Mutual inductance of rings and coils with parallel axes (issue 10, magnetic coupling in a
// bundle), against Maxwell's closed form for coaxial rings and the dipole limit.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "models/inductance/constants.h"
#include "models/inductance/loop_mutual.h"
#include "models/inductance/parallel_coils.h"

using namespace tcpmsim::inductance;

namespace {

// Neumann's double integral (2.1) for two parallel rings, summed directly over n x n points
// (the trapezoidal rule of a periodic integrand): the definition, as a reference for the
// library's single integral.
double neumann_double_sum(double a, double b, double lateral, double axial, int n) {
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    const double t1 = 2.0 * std::numbers::pi * i / n;
    for (int j = 0; j < n; ++j) {
      const double t2 = 2.0 * std::numbers::pi * j / n;
      const double dx = a * std::cos(t1) - lateral - b * std::cos(t2);
      const double dy = a * std::sin(t1) - b * std::sin(t2);
      sum += std::cos(t1 - t2) / std::sqrt(dx * dx + dy * dy + axial * axial);
    }
  }
  const double step = 2.0 * std::numbers::pi / n;
  return mu0 * a * b / (4.0 * std::numbers::pi) * step * step * sum;
}

}  // namespace

TEST_CASE("Maxwell's coaxial formula for unequal radii reduces to (2.11) and to its limits") {
  const double r = 0.8e-3;
  // loop_mutual_inductance is good to 1e-12 from h = 0.01 r, to 1e-10 at 1e-3 r.
  for (double h : {0.01 * r, 0.3 * r, 2.0 * r, 30.0 * r, 1e3 * r}) {
    INFO("h = " << h);
    CHECK(coaxial_loops_mutual_inductance(r, r, h) ==
          Approx(loop_mutual_inductance(r, h)).epsilon(1e-12));
  }
  CHECK(coaxial_loops_mutual_inductance(r, r, 1e-3 * r) ==
        Approx(loop_mutual_inductance(r, 1e-3 * r)).epsilon(1e-10));
  const double a = 1e-3, b = 0.3e-3;
  CHECK(coaxial_loops_mutual_inductance(b, a, 0.7e-3) ==
        Approx(coaxial_loops_mutual_inductance(a, b, 0.7e-3)).epsilon(1e-15));
  // Far apart, two aligned dipoles: mu0 pi a^2 b^2 / (2 h^3), relatively 3 (a^2 + b^2) / h^2 off
  // at most.
  const double h = 0.5;
  CHECK(coaxial_loops_mutual_inductance(a, b, h) ==
        Approx(mu0 * std::numbers::pi * a * a * b * b / (2.0 * h * h * h)).epsilon(1e-5));
  // A small ring at the centre of a large one, in its plane, takes the centre's field
  // mu0 / (2 a) over its area: M -> mu0 pi b^2 / (2 a), off by a relative (b/a)^2 order.
  const double small = 1e-3 * a;
  CHECK(coaxial_loops_mutual_inductance(a, small, 0.0) ==
        Approx(mu0 * std::numbers::pi * small * small / (2.0 * a)).epsilon(1e-5));
  CHECK_THROWS_AS(coaxial_loops_mutual_inductance(r, r, 0.0), std::domain_error);
}

TEST_CASE("The single integral along one ring equals Neumann's double integral over both") {
  struct Rings {
    double a, b, lateral, axial;
  };
  // Side by side in a bundle (0.2 mm apart), offset along the axes, one ring inside the other,
  // and one whose circle passes through the other's axis (rho = 0 on the way).
  for (const Rings& rings :
       {Rings{0.7e-3, 0.7e-3, 1.6e-3, 0.0}, Rings{0.7e-3, 0.7e-3, 1.6e-3, 0.5e-3},
        Rings{1e-3, 0.4e-3, 0.5e-3, 0.0}, Rings{1e-3, 0.4e-3, 0.4e-3, 0.1e-3},
        Rings{0.5e-3, 0.9e-3, 3e-3, 2e-3}}) {
    INFO("a " << rings.a << " b " << rings.b << " lateral " << rings.lateral << " axial "
              << rings.axial);
    const double reference = neumann_double_sum(rings.a, rings.b, rings.lateral, rings.axial, 1024);
    CHECK(parallel_loops_mutual_inductance(rings.a, rings.b, rings.lateral, rings.axial) ==
          Approx(reference).epsilon(1e-10));
  }
}

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
  // A gap of 1e-6 r still converges; at 1e-10 r the rule cannot and says so.
  CHECK(parallel_loops_mutual_inductance(0.7e-3, 0.7e-3, 1.4e-3 * (1.0 + 5e-7), 0.0) < 0.0);
  CHECK_THROWS_WITH(parallel_loops_mutual_inductance(0.7e-3, 0.7e-3, 1.4e-3 * (1.0 + 5e-11), 0.0),
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
