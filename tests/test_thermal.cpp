// The thermal node and the thermal force, against analytic solutions and conservation.
#include <catch2/catch.hpp>

#include <cmath>

#include "models/thermal_force.h"
#include "tests/support/test_support.h"

using namespace tcpmsim;
using namespace tcpmsim::testing;

namespace {
constexpr double kAmbient = 293.15;                     // 20 degC, as in the test muscle
constexpr double kCapacity = 0.5, kConductance = 0.05;  // J/K, W/K: tau = 10 s

double step_response(double t, double step_time, double power) {
  if (t < step_time) return kAmbient;
  return kAmbient +
         power / kConductance * (1.0 - std::exp(-(t - step_time) * kConductance / kCapacity));
}
}  // namespace

TEST_CASE(
    "A power step heats the thermal node with the first-order response T_amb + P/hA (1 - exp(-t "
    "hA/C))") {
  for (double rtol : {1e-6, 1e-9}) {
    const Trace trace =
        simulate(physical_muscle_yaml(),
                 {"solver.rtol=" + number(rtol),
                  "drive.power={type: steps, initial: 0 W, times: [10 s], values: [1.5 W]}"});
    const auto& temperature = trace["muscle/temperature"];
    double worst = 0.0;
    for (std::size_t i = 0; i < trace.time.size(); ++i) {
      worst = std::max(worst, std::abs(temperature[i] - step_response(trace.time[i], 10.0, 1.5)));
    }
    INFO("rtol = " << rtol << ", worst error = " << worst << " K");
    CHECK(worst <= allowed(rtol, 1.5 / kConductance + kAmbient));
  }
}

TEST_CASE("The step-response error shrinks with the solver tolerance") {
  auto worst_error = [](double rtol) {
    const Trace trace =
        simulate(physical_muscle_yaml(),
                 {"solver.rtol=" + number(rtol),
                  "drive.power={type: steps, initial: 0 W, times: [10 s], values: [1.5 W]}"});
    double worst = 0.0;
    for (std::size_t i = 0; i < trace.time.size(); ++i) {
      worst = std::max(worst, std::abs(trace["muscle/temperature"][i] -
                                       step_response(trace.time[i], 10.0, 1.5)));
    }
    return worst;
  };
  CHECK(worst_error(1e-9) < worst_error(1e-5) / 100.0);
}

TEST_CASE("Energy is conserved: integral of P dt = C dT + integral of heat loss, with radiation") {
  // Piecewise-constant power: its integral is exact, independent of the solver.
  const Trace trace =
      simulate(physical_muscle_yaml(), {"muscle.thermal.energy_accounting=true",
                                        "muscle.thermal.radiation={emissivity: 0.9, area: 2 cm^2}",
                                        "drive.power={type: steps, initial: 0.5 W, times: [20 s, "
                                        "45.5 s, 70 s], values: [2 W, 0 W, 1 W]}"});
  const double delivered = 0.5 * 20 + 2.0 * 25.5 + 0.0 * 24.5 + 1.0 * 30;  // J
  const double heat_in = trace["muscle/heat_in"].back();
  const double heat_lost = trace["muscle/heat_lost"].back();
  const double stored = kCapacity * (trace["muscle/temperature"].back() - kAmbient);
  CHECK(heat_in == Approx(delivered).epsilon(allowed(1e-8, 1.0)));
  CHECK(heat_in == Approx(stored + heat_lost).epsilon(allowed(1e-8, 1.0)));
  // The loss integral agrees with a trapezoid rule over the recorded temperature.
  const double area = 2e-4, emissivity = 0.9, sigma = 5.670374419e-8;
  const auto& T = trace["muscle/temperature"];
  double trapezoid = 0.0;
  for (std::size_t i = 1; i < T.size(); ++i) {
    auto loss = [&](double t) {
      return kConductance * (t - kAmbient) +
             emissivity * sigma * area * (std::pow(t, 4) - std::pow(kAmbient, 4));
    };
    trapezoid += 0.5 * (loss(T[i]) + loss(T[i - 1])) * (trace.time[i] - trace.time[i - 1]);
  }
  CHECK(heat_lost == Approx(trapezoid).epsilon(1e-3));  // trapezoid error at 10 Hz sampling
  CHECK(heat_lost > 0.0);
}

TEST_CASE("A one-sample heat pulse is not stepped over") {
  // 50 ms at 20 W in 400 s of nothing: without a hard stop at its edges the solver, taking
  // steps of tens of seconds, would not see it.
  const Trace trace = simulate(
      physical_muscle_yaml(),
      {"scenario.duration=400 s", "muscle.thermal.energy_accounting=true",
       "drive.power={type: steps, initial: 0 W, times: [250 s, 250.05 s], values: [20 W, 0 W]}"});
  CHECK(trace["muscle/heat_in"].back() == Approx(20.0 * 0.05).epsilon(1e-6));
  // Analytic: the pulse raises T by P/hA (1 - exp(-d/tau)), which then decays with tau.
  const double tau = kCapacity / kConductance;
  const double rise = 20.0 / kConductance * (1.0 - std::exp(-0.05 / tau));
  for (std::size_t i = 0; i < trace.time.size(); ++i) {
    const double t = trace.time[i];
    if (t < 250.05) continue;
    const double expected = kAmbient + rise * std::exp(-(t - 250.05) / tau);
    REQUIRE(trace["muscle/temperature"][i] == Approx(expected).margin(allowed(1e-8, 300.0)));
  }
}

TEST_CASE(
    "The reduced thermal force (7.1) equals the physical form under kappa_c = hA/C, kappa_P = "
    "phi_T/C") {
  const std::vector<std::string> excitation{
      "drive.power={type: multisine, components: 7, band: [0.004 Hz, 0.08 Hz], range: [0.1 W, 3 "
      "W]}",
      "load.deflection={type: sine, offset: 20 mm, amplitude: 5 mm, frequency: 0.05 Hz}"};
  const Trace physical = simulate(physical_muscle_yaml(), excitation);
  const Trace reduced = simulate(reduced_muscle_yaml(), excitation);
  CHECK(max_abs_difference(physical["muscle/thermal_force"], reduced["muscle/thermal_force"]) <=
        allowed(1e-8, 0.2));
  CHECK(max_abs_difference(physical["muscle/force"], reduced["muscle/force"]) <=
        allowed(1e-8, 0.5));
  CHECK(max_abs_difference(physical["muscle/temperature"], reduced["muscle/temperature"]) <=
        allowed(1e-8, 400.0));
}

TEST_CASE("The thermal-model mapping gives kappa_P = phi_T/C and kappa_c = hA/C") {
  const auto reduced = thermal_force::reduce(kCapacity, kConductance, 0.002, kAmbient);
  CHECK(reduced.heating_gain == Approx(0.002 / kCapacity));
  CHECK(reduced.cooling_rate == Approx(kConductance / kCapacity));
  CHECK(reduced.ambient_temperature == kAmbient);
  REQUIRE(reduced.force_per_kelvin.has_value());
  CHECK(*reduced.force_per_kelvin == 0.002);
}
