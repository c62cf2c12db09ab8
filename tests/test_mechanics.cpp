// The SLS branch (7.5)-(7.6) and the loads, against their analytic responses.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "tests/support/test_support.h"

using namespace tcpmsim;
using namespace tcpmsim::testing;

namespace {
// The test muscle: k1 = 10 N/m, k2 = 2.5 N/m, c = 5 N s/m, phi_0 = 0.1 N, and no heating.
constexpr double k1 = 10.0, k2 = 2.5, c = 5.0, phi0 = 0.1;
}  // namespace

TEST_CASE("SLS force relaxes after a deflection step with tau = c/k2") {
  const Trace trace =
      simulate(physical_muscle_yaml(),
               {"scenario.duration=20 s", "output.rate=100 Hz",
                "load.deflection={type: steps, initial: 10 mm, times: [1 s], values: [30 mm]}"});
  const double tau = c / k2, x0 = 0.010, x1 = 0.030;
  const auto& force = trace["muscle/force"];
  for (std::size_t i = 0; i < trace.time.size(); ++i) {
    const double t = trace.time[i];
    const double expected =
        t < 1.0 ? k1 * x0 + phi0 : k1 * x1 + k2 * (x1 - x0) * std::exp(-(t - 1.0) / tau) + phi0;
    REQUIRE(force[i] == Approx(expected).margin(allowed(1e-8, 0.5)));
  }
  // The instantaneous response is elastic with k1 + k2; after one tau the excess is 1/e.
  const auto at = [&](double t) { return force[static_cast<std::size_t>(std::lround(t * 100.0))]; };
  CHECK(at(1.0) - at(0.99) == Approx((k1 + k2) * (x1 - x0)).epsilon(1e-6));
  CHECK((at(1.0 + tau) - (k1 * x1 + phi0)) / (at(1.0) - (k1 * x1 + phi0)) ==
        Approx(std::exp(-1.0)).epsilon(1e-6));
}

TEST_CASE("SLS creeps under a force step with tau = c (k1 + k2) / (k1 k2)") {
  const Trace trace = simulate(
      physical_muscle_yaml(),
      {"scenario.duration=30 s", "output.rate=100 Hz",
       "load={type: force, force: {type: steps, initial: 0.2 N, times: [1 s], values: [0.3 N]}}"});
  const double tau = c * (k1 + k2) / (k1 * k2);
  const double x0 = (0.2 - phi0) / k1;                 // relaxed before the step
  const double x_jump = x0 + (0.3 - 0.2) / (k1 + k2);  // elastic response
  const double x_final = (0.3 - phi0) / k1;
  const auto& deflection = trace["muscle/deflection"];
  for (std::size_t i = 0; i < trace.time.size(); ++i) {
    const double t = trace.time[i];
    const double expected =
        t < 1.0 ? x0 : x_final + (x_jump - x_final) * std::exp(-(t - 1.0) / tau);
    REQUIRE(deflection[i] == Approx(expected).margin(allowed(1e-8, 0.03)));
  }
  CHECK(trace["load/deflection"] == deflection);  // the position sensor reads the muscle
}

TEST_CASE(
    "The thermal force adds in parallel (7.5): heating at fixed deflection raises F by phi_T dT") {
  const Trace trace =
      simulate(physical_muscle_yaml(), {"drive.power=1 W", "scenario.duration=300 s"});
  const double dT = trace["muscle/temperature"].back() - 293.15;
  CHECK(dT == Approx(1.0 / 0.05).epsilon(1e-6));  // steady state P/hA after 30 tau
  CHECK(trace["muscle/force"].back() - trace["muscle/force"].front() ==
        Approx(0.002 * dT).epsilon(1e-6));
}

TEST_CASE("A hanging mass on a pure spring oscillates with period 2 pi sqrt(m/k1)") {
  // k2 = 0 leaves the parallel spring k1 only; no damping anywhere.
  const Trace trace =
      simulate(physical_muscle_yaml(),
               {"scenario.duration=10 s", "output.rate=1000 Hz", "muscle.mechanics.k2=0 N/m",
                "load={type: hanging_mass, mass: 50 g, initial_deflection: 30 mm}"});
  const double period = 2.0 * std::numbers::pi * std::sqrt(0.05 / k1);
  const double equilibrium = (0.05 * 9.80665 - phi0) / k1;
  // Upward zero crossings of x - x_eq, interpolated linearly.
  std::vector<double> crossings;
  const auto& x = trace["load/deflection"];
  for (std::size_t i = 1; i < x.size(); ++i) {
    const double a = x[i - 1] - equilibrium, b = x[i] - equilibrium;
    if (a < 0.0 && b >= 0.0)
      crossings.push_back(trace.time[i - 1] + (trace.time[i] - trace.time[i - 1]) * a / (a - b));
  }
  REQUIRE(crossings.size() >= 6);
  const double measured =
      (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
  CHECK(measured == Approx(period).epsilon(1e-5));
  // Energy: amplitude is preserved, 30 mm - x_eq either side.
  const auto [low, high] = std::minmax_element(x.begin(), x.end());
  const double amplitude = std::abs(0.030 - equilibrium);
  CHECK(*high - equilibrium == Approx(amplitude).epsilon(1e-4));
  CHECK(equilibrium - *low == Approx(amplitude).epsilon(1e-4));
}

TEST_CASE("A hanging mass started at equilibrium stays there") {
  const Trace trace =
      simulate(physical_muscle_yaml(),
               {"load={type: hanging_mass, mass: 40 g, initial_deflection: equilibrium}"});
  const double equilibrium = (0.04 * 9.80665 - phi0) / k1;
  for (double x : trace["load/deflection"]) REQUIRE(x == Approx(equilibrium).margin(1e-12));
  for (double f : trace["load/force"]) REQUIRE(f == Approx(0.04 * 9.80665).epsilon(1e-10));
}
