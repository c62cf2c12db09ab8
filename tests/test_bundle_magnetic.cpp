// Magnetic coupling between the coils of a bundle's touching members (issue 10): the mutual
// inductance from the library enters each coil's inductance and the Muscle Drive's L*, biases
// the self-sensed deflection, and an estimator that models it removes the bias.
#include <catch2/catch.hpp>

#include <cmath>
#include <span>
#include <string>
#include <vector>

#include "analysis/statistics.h"
#include "models/bundle/bundle_magnetics.h"
#include "models/inductance/parallel_coils.h"
#include "tests/support/test_support.h"

using namespace tcpmsim;
using namespace tcpmsim::testing;

namespace {

// Table 7.1/7.2's coil in henries: lambda_x = 28.8 mm is the coil's length at rest
// (L = mu0 pi r^2 N^2 / (x + lambda_x)), and lambda_l = mu0 pi r^2 N^2 for r = 0.7 mm, N = 62.
constexpr double kLambdaL = 7.45e-9;  // H m
constexpr double kLambdaX = 28.8e-3;  // m
constexpr double kLambda0 = 1.14799e-6;
constexpr double kDeflection = 20e-3;
constexpr double kPitch = 1.6e-3;
const std::string kCoil =
    "coil: {radius: 0.7 mm, turns: 62, length: 28.8 mm, wire_diameter: 0.1 mm}";

std::string coupled_bundle(int count, const std::string& estimator) {
  return R"(scenario: {name: magnetic, duration: 40 s, seed: 1}
output: {rate: 20 Hz}
bundle:
  count: )" +
         std::to_string(count) +
         R"(
  packing: {layout: hexagonal, pitch: 1.6 mm}
  muscle:
    thermal: {heat_capacity: 0.05 J/K, conductance: 2.5 mW/K, ambient_temperature: 23 degC}
    thermal_force: {form: physical, force_per_kelvin: 4 mN/K, reference_temperature: 23 degC}
    mechanics: {k1: 10.8e-3 N/mm, k2: 2.7e-3 N/mm, damping: 4.3e-3 N*s/mm, force_offset: 0.1 N}
    resistance: 10.18 ohm
    inductance: {lambda_l: 7.4500 uH*mm, lambda_x: 28.8 mm, lambda_0: 1.14799 uH}
  thermal: {shielding: 0.6}
  magnetic: {)" +
         kCoil + R"(}
  electrical:
    wiring: individual
    drive: {model: muscle_drive, fidelity: averaged, supply_voltage: 7 V, series_resistance: 0.57 ohm, measurement: {threshold_current: 14 mA, timing_noise: 3 ns}, power: 0.5 W}
    estimator:
      inductance: {lambda_l: 2.81 us*mm, lambda_x: 28.8 mm, lambda_0: 0.433 us}
      thermal: {kappa_P: 7.2e-3 N/J, kappa_c: 131.6e-3 1/s}
      mechanics: {k1: 10.8e-3 N/mm, k2: 2.7e-3 N/mm, damping: 4.3e-3 N*s/mm, force_offset: 106.9e-3 N}
)" + estimator +
         "load: {type: deflection, bundle: bundle, deflection: 20 mm}\n";
}

const std::string kCompensation =
    "      mutual_compensation: {" + kCoil + ", measure_per_henry: 0.3772 s/H}\n";

double neighbour_mutual() {
  return inductance::parallel_coils_mutual_inductance({0.7e-3, kLambdaX + kDeflection, 62, 0.1e-3},
                                                      kPitch);
}

std::string member(int k, const std::string& channel) {
  return "bundle/m" + std::to_string(k) + channel;
}

// The values from sample `from` on.
std::span<const double> settled_part(const std::vector<double>& values, std::size_t from) {
  return std::span<const double>(values).subspan(from);
}

}  // namespace

TEST_CASE("Each coil's inductance gains its neighbours' mutual inductance, the library's value") {
  // Two touching members: one neighbour each.
  const auto trace = simulate(coupled_bundle(2, ""), {"scenario.duration=1 s"});
  const double self = kLambdaL / (kDeflection + kLambdaX) + kLambda0;  // (6.3)
  const double mutual = neighbour_mutual();
  CHECK(mutual < 0.0);  // side by side, a neighbour's flux returns through the coil
  for (int k = 0; k < 2; ++k) {
    // The bundle interpolates M(x) in a table good to 1e-6 of M (1e-9 of the inductance).
    CHECK(trace[member(k, "/magnetic/mutual_inductance")].back() == Approx(mutual).epsilon(1e-6));
    CHECK(trace[member(k, "/inductance")].back() ==
          Approx(self + trace[member(k, "/magnetic/mutual_inductance")].back()).epsilon(1e-14));
  }
}

TEST_CASE("The bundle's table of M(x) follows the library's sum and holds at its ends") {
  const NeighbourMutual table({0.7e-3, kLambdaX, 62, 0.1e-3}, kPitch);
  CHECK(table.table_error() < 1e-6);
  // Across the table, coil lengths l0 / 4 to 4 l0.
  for (double x : {-20e-3, -14e-3, -5e-3, 0.0, 7e-3, 20e-3, 40e-3, 80e-3}) {
    INFO("x = " << x);
    CHECK(table(x) == Approx(table.direct(x)).epsilon(1e-6));
  }
  CHECK(table(20e-3) == Approx(neighbour_mutual()).epsilon(1e-6));
  // Beyond it the value at the end: the right-hand side never evaluates the full sum.
  const double longest = 4.0 * kLambdaX - kLambdaX;
  CHECK(table(longest + 50e-3) == Approx(table(longest)).epsilon(1e-12));
  CHECK(table(-kLambdaX) == Approx(table(0.25 * kLambdaX - kLambdaX)).epsilon(1e-12));
}

TEST_CASE("Coupling biases self-sensed deflection; the estimator's own model of it removes that") {
  const auto plain = simulate(coupled_bundle(7, ""));
  const auto compensated = simulate(coupled_bundle(7, kCompensation));
  const std::size_t settled = 400;  // after 20 s: the 0.111 Hz low-pass has settled
  const double mutual = neighbour_mutual();
  for (int k = 0; k < 7; ++k) {
    INFO("member " << k);
    const int neighbours = k == 0 ? 6 : 3;
    const double measured = kLambdaL / (kDeflection + kLambdaX) + kLambda0 + neighbours * mutual;
    // (7.4) of the coupled inductance, what an estimator without the coupling must conclude.
    const double biased = kLambdaL / (measured - kLambda0) - kLambdaX;
    const auto& raw = plain[member(k, "/estimator/deflection")];
    const auto& fixed = compensated[member(k, "/estimator/deflection")];
    const double noise = analysis::standard_deviation(settled_part(fixed, settled));
    // The bias: 3.4 mm at the centre, 1.6 mm on the ring, well above the sensing noise.
    CHECK(biased - kDeflection > 3.0 * noise);
    // The same plant and noise in both runs: the compensation shifts the estimate by the bias.
    CHECK(analysis::mean(settled_part(raw, settled)) -
              analysis::mean(settled_part(fixed, settled)) ==
          Approx(biased - kDeflection).epsilon(0.03));
    // Compensated, the estimate's mean error is within its noise.
    CHECK(std::abs(analysis::mean(settled_part(fixed, settled)) - kDeflection) < noise);
  }
}

TEST_CASE("A coil of more turns than the mutual-inductance table can sum is refused at turns") {
  // Issue 31: 1e8 turns ran the ring sums for minutes before anything was refused.
  for (const char* key : {"bundle.magnetic.coil.turns",
                          "bundle.electrical.estimator."
                          "mutual_compensation.coil.turns"}) {
    CHECK_THAT(
        config_error(coupled_bundle(2, kCompensation), {std::string(key) + "=1e8"}),
        Catch::StartsWith("command line (--set " + std::string(key) + "=1e8): error: " + key +
                          ": expected a value in [1, 10000] (the limit: the table of "
                          "M(x) sums an integral per ring offset at 49 lengths), got '1e8'"));
  }
}

TEST_CASE("Magnetic coupling needs henries and a bundle member; coils must not overlap") {
  CHECK_THAT(config_error(coupled_bundle(2, ""), {"bundle.magnetic.coil.radius=0.8 mm"}),
             Catch::Contains("the pitch must exceed the coil's outer diameter"));
  CHECK_THAT(config_error(coupled_bundle(2, ""),
                          {"bundle.muscle.inductance={quantity: measure, lambda_l: 2.81 mm, "
                           "lambda_x: 28.8 mm, lambda_0: 0.433}"}),
             Catch::Contains("bundle.magnetic: mutual inductances are in henries"));
  std::string yaml = coupled_bundle(2, kCompensation);
  const auto magnetic = yaml.find("  magnetic:");
  yaml.erase(magnetic, yaml.find('\n', magnetic) - magnetic + 1);
  CHECK_THAT(config_error(yaml),
             Catch::Contains("mutual_compensation: models a bundle member's coupling"));
}
