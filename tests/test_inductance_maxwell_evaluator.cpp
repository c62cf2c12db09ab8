// The fast evaluator of Maxwell's summation (4.11) against the direct elliptic-integral sum.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <vector>

#include "models/inductance/loop_mutual.h"
#include "models/inductance/maxwell.h"
#include "models/inductance/maxwell_evaluator.h"

using namespace tcpmsim::inductance;

namespace {
// Spring S_T of thesis Table 4.1: 52 windings, r = 8 mm, delta = 2 mm, l from 196 to 264 mm.
constexpr double kRadius = 8e-3, kWire = 2e-3;
constexpr int kWindings = 52;

// Windings of a vibrating spring: uniform over `length` plus a random disturbance of each gap.
std::vector<double> disturbed_positions(std::mt19937& rng, double length, double spread) {
  std::uniform_real_distribution<double> factor(1.0 - spread, 1.0 + spread);
  std::vector<double> positions{0.0};
  for (int i = 1; i < kWindings; ++i) {
    positions.push_back(positions.back() + length / (kWindings - 1) * factor(rng));
  }
  return positions;
}
}  // namespace

TEST_CASE("The tabulated loop mutual inductance matches the direct formula to 1e-11") {
  // The direct formula itself is accurate to ~1e-12 (libstdc++'s K and E, checked against
  // 40-digit values); the degree-9 interpolants add less than that (table_error, measured at
  // construction between the nodes of every segment).
  const MaxwellEvaluator evaluator(kRadius, wire_gmd(kWire), 0.5 * kWire, 0.3);
  CHECK(evaluator.table_error() <= 1e-11);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> exponent(std::log(0.5 * kWire), std::log(0.3));
  double worst = 0.0;
  for (int i = 0; i < 20000; ++i) {
    const double h = std::exp(exponent(rng));
    const double direct = loop_mutual_inductance(kRadius, h);
    worst = std::max(worst, std::abs(evaluator.mutual(h) - direct) / direct);
  }
  CHECK(worst <= 1e-11);
}

TEST_CASE("Outside its table the evaluator falls back to the direct formula") {
  const MaxwellEvaluator evaluator(kRadius, wire_gmd(kWire), 1e-3, 0.1);
  CHECK(evaluator.table_min_distance() <= 1e-3);
  CHECK(evaluator.table_max_distance() >= 0.1);
  for (double h : {1e-5, 2e-4, 0.5, 3.0}) {
    INFO("h = " << h);
    CHECK(evaluator.mutual(h) == loop_mutual_inductance(kRadius, h));
  }
  CHECK(std::isinf(evaluator.mutual(0.0)));
}

TEST_CASE("The fast Maxwell sum equals the direct sum over disturbed windings to 1e-12") {
  const MaxwellEvaluator evaluator(kRadius, wire_gmd(kWire), 0.5 * kWire, 0.3);
  CHECK(evaluator.self_term() == loop_mutual_inductance(kRadius, wire_gmd(kWire)));
  std::mt19937 rng(2020);
  for (double length : {0.196, 0.23, 0.264}) {
    for (double spread : {0.0, 0.1, 0.5}) {
      const auto positions = disturbed_positions(rng, length, spread);
      const double direct = maxwell_positions(kRadius, wire_gmd(kWire), positions);
      INFO("length " << length << ", spread " << spread);
      // Summing ~1300 positive terms each within 1e-11 (see above) keeps the relative error.
      CHECK(std::abs(evaluator.inductance(positions) - direct) / direct <= 1e-11);
    }
  }
}

TEST_CASE("The uniform-winding shortcut equals the pairwise sum") {
  const MaxwellEvaluator evaluator(kRadius, wire_gmd(kWire), 0.5 * kWire, 0.3);
  const double pitch = 0.23 / kWindings;
  std::vector<double> positions;
  for (int i = 0; i < kWindings; ++i) positions.push_back(i * pitch);
  const double direct = maxwell_ring_stack(kRadius, wire_gmd(kWire), kWindings, pitch);
  CHECK(evaluator.inductance_uniform(kWindings, pitch) == Approx(direct).epsilon(1e-11));
  CHECK(evaluator.inductance(positions) == Approx(direct).epsilon(1e-11));
}
