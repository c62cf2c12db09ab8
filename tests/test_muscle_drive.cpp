// The Muscle Drive (thesis 7.2.1): PWM heating, averaged against switched, and the decay-time
// measurement of the coil's inductance.
#include <catch2/catch.hpp>

#include <cmath>

#include "tests/support/test_support.h"

using namespace tcpmsim;
using namespace tcpmsim::testing;

namespace {
// The chapter-7 muscle (Table 7.2) with the coil's inductance in henries: L* = G L with
// G = ln(i0/i_th) / R_m, i0 = 7 V / 10.75 ohm, i_th = 14 mA, so that (7.3) holds in L* [us].
std::string drive_yaml(const std::string& fidelity) {
  return R"(
scenario: {name: drive, duration: 20 s, seed: 3}
output: {rate: 20 Hz}
muscle:
  thermal_force: {form: reduced, kappa_P: 7.2e-3 N/J, kappa_c: 131.6e-3 1/s, ambient_temperature: 23 degC, force_per_kelvin: 4.0e-3 N/K}
  mechanics: {k1: 10.8e-3 N/mm, k2: 2.7e-3 N/mm, damping: 4.3e-3 N*s/mm, force_offset: 106.9e-3 N}
  resistance: 10.18 ohm
  inductance: {lambda_l: 7.4500 uH*mm, lambda_x: 28.8 mm, lambda_0: 1.14799 uH}
drive:
  model: muscle_drive
  fidelity: )" +
         fidelity + R"(
  supply_voltage: 7 V
  series_resistance: 0.57 ohm
  measurement: {threshold_current: 14 mA}
  power: {type: steps, initial: 0.5 W, times: [5 s, 12 s], values: [3 W, 1 W]}
load: {type: deflection, deflection: {type: sine, offset: 20 mm, amplitude: 5 mm, frequency: 0.1 Hz}}
)";
}

constexpr double kPeriod = 0.05, kFullPower = 10.18 * (7.0 / 10.75) * (7.0 / 10.75),
                 kappa_P = 7.2e-3, kappa_c = 131.6e-3;

double decay_time(double deflection) {
  const double inductance = 7.45e-9 / (deflection + 0.0288) + 1.14799e-6;
  return inductance / 10.18 * std::log((7.0 / 10.75) / 0.014);
}
}  // namespace

TEST_CASE("Switched and averaged drives agree on force and temperature within the PWM ripple") {
  const Trace switched = simulate(drive_yaml("switched"));
  const Trace averaged = simulate(drive_yaml("averaged"));
  // The heating's deviation from its period average, integrated over a period, bounds the
  // difference in F_T: |dF_T| <= kappa_P P_on f (1 - f) T <= kappa_P P_full T / 4, and in T by
  // dividing by phi_T = 4 mN/K.
  const double force_bound = kappa_P * kFullPower * kPeriod / 4.0;
  const double force_difference =
      max_abs_difference(switched["muscle/force"], averaged["muscle/force"]);
  const double temperature_difference =
      max_abs_difference(switched["muscle/temperature"], averaged["muscle/temperature"]);
  INFO("force " << force_difference << " N (bound " << force_bound << "), temperature "
                << temperature_difference << " K");
  CHECK(force_difference < force_bound);
  CHECK(temperature_difference < force_bound / 4.0e-3);
  CHECK(force_difference > 0.0);  // they are different models
}

TEST_CASE(
    "The switched drive stops at both edges of every PWM period and measures once per period") {
  Scenario scenario = scenario_from_text(drive_yaml("switched"));
  const Trace trace = simulate(scenario);
  const long periods = std::lround(20.0 / kPeriod);
  CHECK(trace.statistics.segments == 2 * periods);
  CHECK(trace.statistics.events == periods);
}

TEST_CASE("The decay time is L / R ln(i0 / i_th), located on the simulated decay") {
  const Trace trace = simulate(drive_yaml("switched"));
  // The measurement published at a period start is that of the previous off-phase.
  const auto& measure = trace["drive/inductance_measure"];
  const auto& deflection = trace["muscle/deflection"];
  double worst = 0.0;
  for (std::size_t k = 2; k < trace.time.size(); ++k) {
    const double expected = decay_time(deflection[k - 1]);
    worst = std::max(worst, std::abs(measure[k] - expected));
  }
  // 50 ms of deflection change (at most 0.16 mm) moves L* by under 0.2 ns; the location is
  // to under 0.2 ns (the drive's tolerance during the decay).
  CHECK(worst < 0.5e-9);
  // And at 20 mm it is Table 7.2's L* of (7.3): 2.81/(20 + 28.8) + 0.433 = 0.4906 us.
  CHECK(decay_time(0.020) == Approx(0.49058e-6).epsilon(1e-4));
}

TEST_CASE("The switched drive heats the muscle with the power of the quadratic duty law (7.2)") {
  // The switched drive turns the supply on for D^2 of each 50 ms period, D = sqrt(P / P_full):
  // the muscle's thermal force then follows dF_T/dt = kappa_P P - kappa_c F_T (7.1) with the
  // demanded P on average. Solved here for the demanded steps (0.5 W, 3 W from 5 s, 1 W from
  // 12 s). At period boundaries the pulse train differs from its average by under
  // kappa_c T / 2 = 0.33 % of the heating; 1 % is allowed.
  const Trace trace = simulate(drive_yaml("switched"));
  const auto demand = [](double t) { return t < 5 - 1e-9 ? 0.5 : t < 12 - 1e-9 ? 3.0 : 1.0; };
  double expected = 0.0, previous_time = 0.0;
  for (std::size_t k = 0; k < trace.time.size(); ++k) {
    const double t = trace.time[k];
    const double settled = kappa_P * demand(previous_time) / kappa_c;
    expected = settled + (expected - settled) * std::exp(-kappa_c * (t - previous_time));
    previous_time = t;
    if (std::abs(std::remainder(t, 1.0)) > 1e-9 || t < 1.0) continue;
    INFO("t = " << t << " s");
    CHECK(trace["muscle/thermal_force"][k] == Approx(expected).epsilon(0.01));
    CHECK(trace["drive/duty"][k] == Approx(std::sqrt(demand(t) / kFullPower)).epsilon(1e-12));
  }
}

TEST_CASE("The measurement's artefacts have the configured tick, spread and spike rate") {
  Scenario scenario =
      scenario_from_text(drive_yaml("averaged"),
                         {"scenario.duration=500 s", "load.deflection=20 mm", "drive.power=1 W",
                          "drive.measurement={threshold_current: 14 mA, timer_resolution: 1 ns}"});
  const Trace ticks = simulate(scenario);
  for (std::size_t k = 2; k < ticks.time.size(); ++k) {
    REQUIRE(std::abs(std::remainder(ticks["drive/inductance_measure"][k], 1e-9)) < 1e-15);
    REQUIRE(ticks["drive/inductance_measure"][k] ==
            Approx(std::floor(decay_time(0.020) / 1e-9) * 1e-9));
  }
  Scenario noisy =
      scenario_from_text(drive_yaml("averaged"),
                         {"scenario.duration=500 s", "load.deflection=20 mm", "drive.power=1 W",
                          "drive.measurement={threshold_current: 14 mA, timing_noise: 2 ns, "
                          "spike_probability: 0.05, spike_size: 100 ns}"});
  const Trace trace = simulate(noisy);
  std::vector<double> errors;
  long spikes = 0;
  for (std::size_t k = 2; k < trace.time.size(); ++k) {
    const double error = trace["drive/inductance_measure"][k] - decay_time(0.020);
    if (std::abs(error) > 50e-9) {
      ++spikes;
    } else {
      errors.push_back(error);
    }
  }
  double mean = 0.0, variance = 0.0;
  for (double e : errors) mean += e / static_cast<double>(errors.size());
  for (double e : errors)
    variance += (e - mean) * (e - mean) / static_cast<double>(errors.size() - 1);
  const double samples = static_cast<double>(trace.time.size() - 2);
  // 10 000 samples: the spread within 3 % of 2 ns and the spike count within 4 sigma of 5 %.
  CHECK(std::sqrt(variance) == Approx(2e-9).epsilon(0.03));
  CHECK(std::abs(static_cast<double>(spikes) - 0.05 * samples) <
        4.0 * std::sqrt(0.05 * 0.95 * samples));
}
