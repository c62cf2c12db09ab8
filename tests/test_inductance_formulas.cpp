// Closed-form coil inductance (thesis ch. 2): Nagaoka, Rosa, the loop mutual inductance and
// Maxwell's summation, each against values from independent sources.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "models/inductance/constants.h"
#include "models/inductance/loop_mutual.h"
#include "models/inductance/maxwell.h"
#include "models/inductance/rosa.h"
#include "models/inductance/solenoid.h"

using namespace tcpmsim::inductance;

namespace {
double relative(double value, double reference) {
  return std::abs(value - reference) / std::abs(reference);
}
}  // namespace

TEST_CASE("Nagaoka's coefficient is 0.68842 for a coil as long as it is wide") {
  // physics.md's check value, to its five digits.
  CHECK(std::abs(nagaoka_coefficient(1.0) - 0.68842) <= 0.5e-5);
}

TEST_CASE("Nagaoka's coefficient reproduces the classical four-digit table") {
  // Nagaoka's K against diameter/length, as tabulated by Nagaoka (1909) and reprinted by Rosa &
  // Grover (Bull. Bureau of Standards 8, 1912) and Grover (Inductance Calculations, 1946).
  // Four printed decimals: agreement to half a unit of the last digit.
  const std::vector<std::pair<double, double>> table{{0.1, 0.9588}, {0.2, 0.9201}, {0.5, 0.8181},
                                                     {1.0, 0.6884}, {2.0, 0.5255}, {5.0, 0.3198},
                                                     {10.0, 0.2033}};
  for (const auto& [u, kappa] : table) {
    INFO("2r/l = " << u);
    CHECK(std::abs(nagaoka_coefficient(u) - kappa) <= 0.5e-4 + 1e-12);
  }
}

TEST_CASE("Nagaoka's coefficient agrees with Lundin's handbook formula for long coils") {
  // R. Lundin, "A handbook formula for the inductance of a single-layer circular coil",
  // Proc. IEEE 73 (1985) 1428: for 2r/l <= 1, kappa = f1(u^2) - 4u/(3 pi) with
  // f1(x) = (1 + 0.383901 x + 0.017108 x^2)/(1 + 0.258952 x), stated accurate to +-3 ppm.
  for (double u = 0.02; u <= 1.0 + 1e-12; u += 0.02) {
    const double x = u * u;
    const double lundin = (1.0 + 0.383901 * x + 0.017108 * x * x) / (1.0 + 0.258952 * x) -
                          4.0 * u / (3.0 * std::numbers::pi);
    INFO("2r/l = " << u);
    CHECK(std::abs(nagaoka_coefficient(u) - lundin) <= 3e-6);
  }
}

TEST_CASE("Nagaoka's coefficient tends to one for long coils, as its series says") {
  // Long-coil expansion kappa = 1 - 4u/(3 pi) + u^2/8 - u^4/64 + O(u^6), u = 2r/l: the error of
  // the first three terms is u^4/64 to leading order.
  CHECK(nagaoka_coefficient(0.0) == 1.0);
  for (double u : {1e-2, 1e-3, 1e-4, 1e-6}) {
    const double series = 1.0 - 4.0 * u / (3.0 * std::numbers::pi) + u * u / 8.0;
    INFO("2r/l = " << u);
    CHECK(std::abs(nagaoka_coefficient(u) - series) <= 1.1 * std::pow(u, 4) / 64.0 + 1e-15);
  }
}

TEST_CASE("Basic and Nagaoka inductances scale as N^2 r^2 / l with mu0 = 4 pi 1e-7") {
  // An ideal long solenoid: 1000 turns, r = 1 cm, l = 1 m: mu0 N^2 pi r^2 / l = 394.78 uH.
  const CoilGeometry coil{0.01, 1.0, 1000.0, 1e-4};
  CHECK(basic_solenoid_inductance(coil) ==
        Approx(4e-7 * std::numbers::pi * 1e6 * std::numbers::pi * 1e-4).epsilon(1e-14));
  CHECK(nagaoka_inductance(coil) ==
        Approx(basic_solenoid_inductance(coil) * nagaoka_coefficient(0.02)).epsilon(1e-14));
  CHECK(mu0 == 4e-7 * std::numbers::pi);
}

TEST_CASE("Two coaxial loops far apart couple like two magnetic dipoles") {
  // M -> mu0 pi r^4 / (2 h^3), with a relative correction -3 (r/h)^2 (from the series of K and
  // E in k^2 ~ 4 r^2/h^2).
  const double r = 0.01;
  for (double ratio : {10.0, 100.0, 1000.0, 1e4}) {
    const double h = ratio * r;
    const double dipole = mu0 * std::numbers::pi * std::pow(r, 4) / (2.0 * std::pow(h, 3));
    const double m = loop_mutual_inductance(r, h);
    INFO("h/r = " << ratio);
    CHECK(m < dipole);
    CHECK(relative(m, dipole) <= 3.5 / (ratio * ratio));
    // The next term is +9.375 (r/h)^4 (same series).
    CHECK(relative(m, dipole * (1.0 - 3.0 / (ratio * ratio))) <=
          std::max(10.0 / std::pow(ratio, 4), 1e-13));
  }
}

TEST_CASE("Two coaxial loops close together follow mu0 r (ln(8r/h) - 2)") {
  // Maxwell's near-field expansion; the next terms are of relative order (h/r)^2 ln(8r/h).
  const double r = 0.01;
  for (double ratio : {1e-2, 1e-3}) {
    const double h = ratio * r;
    const double near = mu0 * r * (std::log(8.0 / ratio) - 2.0);
    INFO("h/r = " << ratio);
    CHECK(relative(loop_mutual_inductance(r, h), near) <= ratio * ratio);
  }
}

TEST_CASE("A ring of round wire has the textbook self-inductance mu0 r (ln(8r/a) - 7/4)") {
  // Rosa & Grover (1912) / Grover (1946): thin circular ring of round wire, radius a, uniform
  // current. Maxwell's summation gets it as M(g) with the gmd g = a e^(-1/4).
  const double r = 0.05;
  for (double a : {0.5e-3, 0.05e-3}) {
    const double ring = mu0 * r * (std::log(8.0 * r / a) - 1.75);
    INFO("a = " << a);
    CHECK(relative(loop_mutual_inductance(r, wire_gmd(2.0 * a)), ring) <= 4.0 * (a / r) * (a / r));
  }
  CHECK(wire_gmd(2e-3) == Approx(1e-3 * std::exp(-0.25)).epsilon(1e-15));
}

TEST_CASE("Rosa's mutual correction reproduces Grover's table, by series and closed form") {
  // Grover, Inductance Calculations (1946) p. 150, as reproduced by D.W. Knight, "Rosa's mutual
  // inductance correction for the round-wire solenoid" (g3ynh.info, 2010). Four decimals of a
  // hand computation: entries at a rounding boundary may be one unit off (N = 30: the series
  // gives 0.307953, the table 0.3079), hence 0.6 units of the last digit.
  const std::vector<std::pair<int, double>> table{{2, 0.1137},  {3, 0.1663},  {4, 0.1973},
                                                  {5, 0.2180},  {10, 0.2664}, {20, 0.2964},
                                                  {30, 0.3079}, {50, 0.3182}, {100, 0.3269}};
  for (const auto& [n, b] : table) {
    INFO("N = " << n);
    CHECK(std::abs(rosa_mutual_correction_series(n) - b) <= 0.6e-4);
    CHECK(std::abs(rosa_mutual_correction_weaver(n) - b) <= 0.6e-4);
  }
  CHECK(rosa_mutual_correction_series(1.0) == 0.0);
}

TEST_CASE("Rosa's series (2.10) sums to 3/2 - 2 ln 2 for two turns") {
  // B(2) = inner sum at i = 1; summing its terms directly (they fall as 1/(4 j^3), the tail
  // after J terms is ~1/(8 J^2)) approaches the closed form used in the code.
  double direct = 0.0;
  const int terms = 200000;
  for (int j = 1; j <= terms; ++j) direct += 1.0 / (2 * j) + 1.0 / (2 * j + 2) - 2.0 / (2 * j + 1);
  CHECK(std::abs(direct - (1.5 - 2.0 * std::numbers::ln2)) <= 1.0 / (8.0 * terms * terms) * 1.01);
  CHECK(rosa_mutual_correction_series(2.0) == Approx(1.5 - 2.0 * std::numbers::ln2).epsilon(1e-15));
}

TEST_CASE("Weaver's closed form of B agrees with the series within Knight's stated 1.3e-8") {
  // Knight (2010) states the extended Grover series (physics.md's form) is accurate to
  // +-0.000 000 013 against Weaver's exact values.
  for (int n = 2; n <= 400; ++n) {
    INFO("N = " << n);
    CHECK(std::abs(rosa_mutual_correction_weaver(n) - rosa_mutual_correction_series(n)) <= 1.4e-8);
  }
}

TEST_CASE("Rosa's correction uses natural logarithms and lowers close-wound coils") {
  // (2.9) at p = delta: A = 5/4 - ln 2 = 0.5569.
  CHECK(rosa_self_correction(1e-3, 1e-3) == Approx(1.25 - std::numbers::ln2).epsilon(1e-15));
  const CoilGeometry coil{0.01, 0.02, 20.0, 1e-3};
  CHECK(rosa_inductance(coil) < nagaoka_inductance(coil));
  CHECK(rosa_inductance(coil, RosaMutualCorrection::series) ==
        Approx(rosa_inductance(coil, RosaMutualCorrection::weaver)).epsilon(1e-8));
}

TEST_CASE("Maxwell's ring sum approaches Rosa's corrected Nagaoka as pitch/radius shrinks") {
  // Rosa's A and B are derived with the geometric-mean-distance method for turns that are close
  // compared with the radius; the neglected curvature terms are of relative order (p/r)^2.
  for (int n : {10, 43, 100}) {
    for (double r : {5e-3, 10e-3, 20e-3, 50e-3}) {
      for (double pitch_over_wire : {1.0, 1.5, 3.0}) {
        const double delta = 1e-3;
        const CoilGeometry coil{r, n * delta * pitch_over_wire, static_cast<double>(n), delta};
        const double p_over_r = coil.pitch() / r;
        INFO("N = " << n << ", r = " << r << ", p/delta = " << pitch_over_wire);
        const double rosa = rosa_inductance(coil, RosaMutualCorrection::series);
        CHECK(relative(rosa, maxwell_inductance(coil)) <= p_over_r * p_over_r);
        // The bound is loose where p/r is large; the correction must still move Nagaoka's
        // current sheet towards the ring sum.
        CHECK(relative(rosa, maxwell_inductance(coil)) <
              relative(nagaoka_inductance(coil), maxwell_inductance(coil)));
      }
    }
  }
}

TEST_CASE("Maxwell's uniform sum equals the sum over the same positions") {
  const double r = 8e-3, g = wire_gmd(2e-3), pitch = 3.9e-3;
  std::vector<double> positions;
  for (int i = 0; i < 52; ++i) positions.push_back(0.1 + i * pitch);
  const double uniform = maxwell_ring_stack(r, g, 52, pitch);
  CHECK(maxwell_positions(r, g, positions) == Approx(uniform).epsilon(1e-13));
  // With an integer N the thesis' protocol is the plain ring stack.
  CHECK(maxwell_inductance({r, 52 * pitch, 52.0, 2e-3}) == Approx(uniform).epsilon(1e-13));
  // Order does not matter.
  std::swap(positions[3], positions[40]);
  CHECK(maxwell_positions(r, g, positions) == Approx(uniform).epsilon(1e-13));
}
