// The fitted spring model (2.14): calibration and inversion.
#include <catch2/catch.hpp>

#include <vector>

#include "models/inductance/spring_inductance_fit.h"

using tcpmsim::inductance::SpringInductanceFit;

TEST_CASE("A two-point calibration passes through both points and inverts exactly") {
  // Two points of an exact L = alpha/l + beta (alpha = 463.5 uH mm, beta = 0.095 uH, S1-like).
  const double alpha = 463.5e-9, beta = 0.095e-6;
  const double l1 = 0.124, l2 = 0.177;
  const auto fit = SpringInductanceFit::two_point(l1, alpha / l1 + beta, l2, alpha / l2 + beta);
  CHECK(fit.alpha() == Approx(alpha).epsilon(1e-13));
  CHECK(fit.beta() == Approx(beta).epsilon(1e-12));
  CHECK(fit.inductance(l1) == Approx(alpha / l1 + beta).epsilon(1e-14));
  for (double l = 0.10; l < 0.20; l += 0.01) {
    INFO("l = " << l);
    CHECK(fit.length(fit.inductance(l)) == Approx(l).epsilon(1e-13));
  }
  CHECK_THROWS_AS(SpringInductanceFit::two_point(l1, 1e-6, l1, 2e-6), std::invalid_argument);
}

TEST_CASE("A least-squares calibration recovers an exact law and averages symmetric noise") {
  const double alpha = 860e-9, beta = 0.46e-6;
  std::vector<double> lengths, exact, noisy;
  for (int i = 0; i < 10; ++i) {
    lengths.push_back(0.1 + 0.005 * i);
    exact.push_back(alpha / lengths.back() + beta);
    // +-e at each length: symmetric pairs leave the least-squares line unchanged.
    noisy.push_back(exact.back());
    noisy.push_back(exact.back());
  }
  auto fit = SpringInductanceFit::least_squares(lengths, exact);
  CHECK(fit.alpha() == Approx(alpha).epsilon(1e-12));
  CHECK(fit.beta() == Approx(beta).epsilon(1e-11));
  std::vector<double> doubled_lengths;
  for (std::size_t i = 0; i < lengths.size(); ++i) {
    doubled_lengths.push_back(lengths[i]);
    doubled_lengths.push_back(lengths[i]);
    noisy[2 * i] += 3e-9;
    noisy[2 * i + 1] -= 3e-9;
  }
  fit = SpringInductanceFit::least_squares(doubled_lengths, noisy);
  CHECK(fit.alpha() == Approx(alpha).epsilon(1e-11));
  CHECK(fit.beta() == Approx(beta).epsilon(1e-10));
}

TEST_CASE("The fitted spring model is the TCPM law (6.3) with lambda_x = 0") {
  const SpringInductanceFit fit(500e-9, 0.1e-6);
  CHECK(fit.law().lambda_l == 500e-9);
  CHECK(fit.law().lambda_x == 0.0);
  CHECK(fit.law().lambda_T == 0.0);
  CHECK(fit.law().lambda_0 == 0.1e-6);
  // (7.4) inverts (7.3): the same length back.
  CHECK(fit.law().deflection(fit.inductance(0.15), 300.0) == Approx(0.15).epsilon(1e-14));
}
