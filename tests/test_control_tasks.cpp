// The chapter-7 control tasks through the engine: the thesis comparison command, what the
// power limits make reachable, and the describing-function verdicts confirmed in simulation.
#include <catch2/catch.hpp>

#include <cmath>
#include <complex>
#include <filesystem>
#include <limits>
#include <mutex>
#include <numbers>
#include <sstream>
#include <string>
#include <utility>

#include "analysis/control_task_runner.h"
#include "analysis/control_tasks_command.h"
#include "analysis/describing_function.h"
#include "sim/io/hdf5_files.h"
#include "tests/support/test_support.h"

using namespace tcpmsim;
using namespace tcpmsim::testing;

namespace {
// Table 7.2.
constexpr double kappa_P = 7.2e-3, kappa_c = 131.6e-3, k1 = 10.8, k2 = 2.7, damping = 4.3,
                 phi0 = 106.9e-3, P_min = 0.10, P_max = 3.12;

std::vector<std::string> control_configs() {
  std::vector<std::string> configs;
  for (const char* name : {"deflection_steps", "deflection_sweep", "force_steps", "force_sweep"}) {
    configs.push_back(source_path(std::string("configs/ch7_control/") + name + ".yaml"));
  }
  return configs;
}

// Force control at a fixed 20 mm, L* without artefacts (the describing-function setting), with a
// reachable constant reference of 0.45 N.
Trace force_loop(const std::string& gains, double seconds) {
  Scenario scenario =
      load_scenario(source_path("configs/ch7_control/force_steps.yaml"),
                    {"scenario.duration=" + std::to_string(seconds) + " s",
                     "drive.measurement={threshold_current: 14 mA}",
                     "controller={target: force, reference: 0.45 N, gains: " + gains +
                         ", power_limits: [0.10 W, 3.12 W]}"},
                    shared_units());
  return simulate(scenario);
}
}  // namespace

TEST_CASE(
    "The control-task command calibrates, runs all four tasks and reports beside the thesis") {
  ControlTasksOptions options;
  options.configs = control_configs();
  options.output = (std::filesystem::temp_directory_path() / "tcpmsim_control_tasks.h5").string();
  std::ostringstream out;
  run_control_tasks_command(options, out, shared_units());
  const std::string report = out.str();
  // The thesis' numbers are data: printed from thesis_control_results as the thesis prints them
  // (section 7.4), and kept in the record in SI units.
  CHECK_THAT(report, Catch::Contains("thesis 4.2-14.1 s"));
  CHECK_THAT(report, Catch::Contains("thesis 0.039 Hz"));
  CHECK_THAT(report, Catch::Contains("thesis 0.056 Hz"));
  CHECK_THAT(report, Catch::Contains("thesis -0.27 +- 2.14 mm"));
  CHECK_THAT(report, Catch::Contains("thesis +7.5 +- 29.0 mN"));
  {
    std::lock_guard lock(hdf5_mutex());
    const H5::H5File file(options.output, H5F_ACC_RDONLY);
    for (const bool deflection : {true, false}) {
      const PublishedControlResults thesis = thesis_control_results(deflection);
      const H5::Group group =
          file.openGroup(std::string("thesis_7_4/") + (deflection ? "deflection" : "force"));
      CHECK(read_doubles(group, "rise_time_range") ==
            std::vector<double>{thesis.rise_time_min, thesis.rise_time_max});
      CHECK(read_doubles(group, "bandwidth") == std::vector<double>{thesis.bandwidth});
      CHECK(read_doubles(group, "estimation_error_mean") == std::vector<double>{thesis.error_mean});
      CHECK(read_doubles(group, "estimation_error_half_width_95") ==
            std::vector<double>{thesis.error_half_width});
    }
  }
  std::filesystem::remove(options.output);
}

TEST_CASE("Calibration adds its measured offsets to those the scenario configures") {
  ControlTaskSettings settings;
  settings.overrides = {"scenario.duration=60 s"};
  const std::string config = control_configs()[2];
  const auto plain = run_control_tasks({config}, settings, shared_units());
  settings.overrides.push_back(
      "estimator.calibration={deflection_offset: 1 mm, force_offset: 10 mN}");
  const auto configured = run_control_tasks({config}, settings, shared_units());
  // The hold-deflection run sees the estimate 1 mm high and measures 1 mm less; the force run,
  // its deflection already calibrated, sees the force 10 mN high. What the task's estimator ends
  // with, configured plus measured, is the same, and so is every estimation error.
  CHECK(configured[0].deflection_offset == Approx(plain[0].deflection_offset - 1e-3).margin(1e-12));
  CHECK(configured[0].force_offset == Approx(plain[0].force_offset - 10e-3).margin(1e-9));
  REQUIRE(configured[0].estimation_errors.size() == plain[0].estimation_errors.size());
  for (std::size_t k = 0; k < plain[0].estimation_errors.size(); ++k) {
    CHECK(configured[0].estimation_errors[k] == Approx(plain[0].estimation_errors[k]).margin(1e-9));
  }
}

TEST_CASE("The estimation error is the estimate minus the truth") {
  // Recomputed here from the run's own channels: the deflection task's error at every sample of
  // the task is estimator/deflection - muscle/deflection, sign included.
  ControlTaskSettings settings;
  settings.calibrate = false;
  settings.overrides = {"scenario.duration=60 s"};
  const auto results = run_control_tasks({control_configs()[0]}, settings, shared_units());
  const Trace trace =
      simulate(load_scenario(control_configs()[0], settings.overrides, shared_units()));
  const auto& errors = results[0].estimation_errors;
  REQUIRE(errors.size() > 100);
  REQUIRE(errors.size() <= trace.time.size());
  const std::size_t first = trace.time.size() - errors.size();
  for (std::size_t k = 0; k < errors.size(); ++k) {
    const double expected =
        trace["estimator/deflection"][first + k] - trace["muscle/deflection"][first + k];
    REQUIRE(errors[k] == Approx(expected).margin(1e-12));
  }
}

TEST_CASE(
    "Without sensing artefacts the force task's estimation error vanishes: plant and model "
    "agree") {
  // The estimator models the plant with the plant's own Table 7.2 (7.1), (7.5)-(7.6); at the
  // held 20 mm the deflection estimate is exact once L* is (no timer, jitter or spikes), and
  // F_T^ integrates (7.1) from the delivered power exactly (zero-order hold, as the averaged
  // drive delivers it). What is left: the solver (rtol 1e-8 here) and the config's inductance
  // law in henries, lambda_0 = 1.14799 uH to six digits against the estimator's 0.433 us,
  // i.e. L* within 2e-12 s, x within 1.7 um by (7.4)'s slope 1.18 ns/mm, F within
  // k1 x 1.7 um = 1.8e-5 N. With the artefacts the band is 9 mN.
  ControlTaskSettings settings;
  settings.calibrate = false;
  settings.overrides = {"drive.measurement={threshold_current: 14 mA}", "solver.rtol=1e-8"};
  const auto clean = run_control_tasks({control_configs()[2]}, settings, shared_units());
  REQUIRE(clean[0].estimation_errors.size() > 1000);
  double largest = 0.0;
  for (const double e : clean[0].estimation_errors) largest = std::max(largest, std::abs(e));
  CHECK(largest < 1.8e-5);
}

TEST_CASE("Force control at Table 7.2 reaches the published bandwidth, set by the power limits") {
  ControlTaskSettings settings;
  const auto results = run_control_tasks({control_configs()[3]}, settings, shared_units());
  REQUIRE(results[0].bandwidth.has_value());
  // Thesis 7.4: 0.056 Hz. With Kp = 540 W/N the drive saturates on every cycle, so the
  // bandwidth is the power range's, which our plant (Table 7.2 itself) shares with the thesis'.
  // The thesis prints two digits (+-0.9 %) and the sweep interpolates within 0.7 %
  // (test_control_analysis); the rest is its real muscle against the Table 7.2 model.
  CHECK(*results[0].bandwidth == Approx(thesis_control_results(false).bandwidth).epsilon(0.03));
}

TEST_CASE(
    "Both sweeps' bandwidths, ours and the thesis', lie under the bound the power limits set") {
  // Powers within [P_min, P_max] have a fundamental of at most (4/pi)(P_max - P_min)/2 (a square
  // wave's), and from P to the controlled quantity the plant is linear: (7.1) gives F_T =
  // kappa_P / (j w + kappa_c) P; at fixed deflection the force follows F_T, and under a fixed
  // force the deflection follows -F_T / K(w), K = k1 + k2 j w tau / (1 + j w tau), tau = c / k2
  // (7.5)-(7.6). The response's fundamental can reach the -3 dB level (1/sqrt 2 of the
  // reference's amplitude: 5 mm, 50 mN) only below the frequency where that largest amplitude
  // equals it.
  constexpr double tau = damping / k2;
  const auto largest_amplitude = [&](double frequency, bool deflection) {
    const std::complex<double> jw(0.0, 2.0 * std::numbers::pi * frequency);
    const double thermal =
        kappa_P * (2.0 / std::numbers::pi) * (P_max - P_min) / std::abs(jw + kappa_c);
    return deflection ? thermal / std::abs(k1 + k2 * jw * tau / (1.0 + jw * tau)) : thermal;
  };
  const auto bound = [&](bool deflection, double amplitude) {
    double low = 1e-3, high = 1.0;  // the largest amplitude falls with frequency: bisect
    for (int i = 0; i < 60; ++i) {
      const double middle = std::sqrt(low * high);
      (largest_amplitude(middle, deflection) > amplitude / std::sqrt(2.0) ? low : high) = middle;
    }
    return low;
  };
  ControlTaskSettings settings;
  const auto results =
      run_control_tasks({control_configs()[1], control_configs()[3]}, settings, shared_units());
  for (const auto& result : results) {
    const bool deflection = result.controls_deflection;
    const double limit = bound(deflection, deflection ? 5e-3 : 50e-3);
    INFO((deflection ? "deflection" : "force") << " sweep: bound " << limit << " Hz");
    REQUIRE(result.bandwidth.has_value());
    CHECK(*result.bandwidth <= limit);
    CHECK(thesis_control_results(deflection).bandwidth <= limit);
    // The gains saturate the drive on every cycle, a relay whose power is the square wave: the
    // loop comes close to the bound (ours within 10 %; the thesis' hardware deflection loop,
    // with lags the model leaves out, at 0.039 Hz, 22 % below it).
    CHECK(*result.bandwidth >= 0.9 * limit);
  }
}

TEST_CASE("A plant that heats harder than the estimator's model biases only the force estimate") {
  // Plant and model stay separate: the plant is a physical thermal node (C, hA, phi_T) whose
  // heating gain phi_T/C is 25 % above the estimator's kappa_P, with the same kappa_c. L* does
  // not see temperature, so the deflection loop still holds x at 20 mm under 0.40 N, and at
  // rest the plant's F_T = F - k1 x - phi_0 needs P* = F_T hA/phi_T. The estimator's model
  // turns P* into kappa_P/kappa_c P* = F_T / 1.25: the force estimate is low by F_T / 5.
  const double plant_heating = 1.25 * kappa_P, force_per_kelvin = 4e-3;
  const double capacity = force_per_kelvin / plant_heating, conductance = kappa_c * capacity;
  Scenario scenario = load_scenario(
      source_path("configs/ch7_control/deflection_steps.yaml"),
      {"scenario.duration=120 s", "drive.measurement={threshold_current: 14 mA}",
       "controller={target: deflection, reference: 20 mm, gains: {proportional: -1.08 W/mm, "
       "integral_time: 2.5 s, derivative_time: 0.625 s}, power_limits: [0.10 W, 3.12 W]}",
       "muscle.thermal={heat_capacity: " + number(capacity) +
           " J/K, conductance: " + number(conductance) +
           " W/K, ambient_temperature: 23 degC, initial_temperature: 23 degC}",
       "muscle.thermal_force={form: physical, force_per_kelvin: 4 mN/K, reference_temperature: 23 "
       "degC}"},
      shared_units());
  const Trace trace = simulate(scenario);
  const double thermal_force = 0.40 - k1 * 0.020 - phi0;
  const double operating_power = thermal_force * conductance / force_per_kelvin;
  const std::size_t settled = trace.time.size() - 200;  // the last 10 s
  const auto mean_from = [&](const std::string& channel) {
    const auto& values = trace[channel];
    double sum = 0.0;
    for (std::size_t k = settled; k < values.size(); ++k) sum += values[k];
    return sum / static_cast<double>(values.size() - settled);
  };
  CHECK(mean_from("muscle/deflection") == Approx(0.020).epsilon(1e-4));
  CHECK(mean_from("controller/power_command") == Approx(operating_power).epsilon(1e-3));
  CHECK(mean_from("estimator/force") - mean_from("muscle/force") ==
        Approx(-thermal_force / 5.0).epsilon(1e-3));
}

TEST_CASE("The printed force gain is the one of its decade that reproduces the bandwidth") {
  // Is Kp = 540 W/N a misprint? Any gain whose proportional band (3.02 W / Kp) is well under
  // the sweep's 50 mN amplitude turns the loop into a relay bounded by the power limits, so
  // 54 W/N reproduces the 0.056 Hz as well; 5.4 W/N does not. 5400 W/N would too, but lies
  // within 6 % of the sampled loop's stability limit (10.55 Kp, test_describing_function),
  // which a tuned loop would not. The printed value stands.
  ControlTaskSettings settings;
  settings.calibrate = false;
  for (const auto& [gain, reproduces] : {std::pair{"54 W/N", true}, std::pair{"5.4 W/N", false}}) {
    settings.overrides = {std::string("controller.gains.proportional=") + gain};
    const auto results = run_control_tasks({control_configs()[3]}, settings, shared_units());
    REQUIRE(results[0].bandwidth.has_value());
    INFO("Kp = " << gain << ": " << *results[0].bandwidth << " Hz");
    CHECK((std::abs(*results[0].bandwidth - 0.056) < 0.1 * 0.056) == reproduces);
  }
}

TEST_CASE("A force step is reached exactly when full power gets there within its hold") {
  // At a fixed 20 mm the force is F = k1 x + F_T + phi0 (the dashpot stays relaxed), and with
  // Kp = 540 W/N any error over 5.6 mN saturates the drive, so F_T moves by (7.1) at P_max (or
  // P_min): F_T(t) = F_inf + (F_T0 - F_inf) exp(-kappa_c t). The 90 % level is reached after
  // t = ln((F_inf - F_T0) / (F_inf - F_level)) / kappa_c, if ever.
  ControlTaskSettings settings;
  settings.calibrate = false;
  const auto results = run_control_tasks({control_configs()[2]}, settings, shared_units());
  REQUIRE(results[0].rises.size() == 7);
  for (const auto& rise : results[0].rises) {
    const bool up = rise.target > rise.start;
    const double f_inf = kappa_P / kappa_c * (up ? P_max : P_min);
    const double elastic = k1 * 0.020 + phi0;
    const double level = rise.start + 0.9 * (rise.target - rise.start);
    const double ratio = (f_inf - (rise.start - elastic)) / (f_inf - (level - elastic));
    const double needed =
        ratio > 0.0 ? std::log(ratio) / kappa_c : std::numeric_limits<double>::infinity();
    INFO("step at " << rise.step_time << " s to " << rise.target << " N needs " << needed << " s");
    if (needed < rise.hold - 1.0) {
      CHECK(rise.reached);
      CHECK(rise.upper_time - rise.step_time ==
            Approx(needed).margin(0.2));  // sampling, 10 % start
    }
    if (needed > rise.hold + 1.0) CHECK_FALSE(rise.reached);
  }
}

TEST_CASE("Deflection steps beyond what the power limits hold at 0.40 N are never reached") {
  ControlTaskSettings settings;
  settings.calibrate = false;
  const auto results = run_control_tasks({control_configs()[0]}, settings, shared_units());
  // Steady states of (7.1), (7.5), (7.6) at 0.40 N: x = (F - F_T - phi0) / k1 with
  // F_T = (kappa_P / kappa_c) P in [P_min, P_max]: about 11.3 to 26.6 mm.
  const double x_low = (0.40 - kappa_P / kappa_c * P_max - phi0) / k1;
  const double x_high = (0.40 - kappa_P / kappa_c * P_min - phi0) / k1;
  int unreachable = 0;
  for (const auto& rise : results[0].rises) {
    const double level = rise.start + 0.9 * (rise.target - rise.start);
    INFO("step at " << rise.step_time << " s to " << rise.target);
    if (level < x_low || level > x_high) {
      ++unreachable;
      CHECK_FALSE(rise.reached);
    } else {
      CHECK(rise.reached);
    }
  }
  CHECK(unreachable == 2);  // the steps to 10 and 30 mm
  // Charged their hold as the thesis charges its outliers, and printed as more than it.
  const std::string report = format_control_task_report(results);
  CHECK_THAT(report, Catch::Contains("rise > ") &&
                         Catch::Contains(" s (not reached within its hold)"));
}

TEST_CASE("The thesis' force gains are predicted stable and settle in simulation") {
  const PidGains gains{540.0, 1.0, 0.0};
  const auto loop = force_control_loop(gains, kappa_P, kappa_c, 0.05);
  SlsParameters mechanics{k1, 2.7, 4.3, phi0};
  const double operating = equilibrium_power(0.45, 0.020, kappa_P, kappa_c, mechanics);
  const auto prediction = predict_limit_cycle(loop, {P_min, P_max}, operating);
  REQUIRE(prediction.verdict == LoopVerdict::stable);
  const Trace trace = force_loop("{proportional: 540 W/N, integral_time: 1 s}", 120.0);
  // After the transient the command is constant: the settled operating power P*.
  const auto& power = trace["controller/power_command"];
  for (std::size_t k = power.size() - 200; k < power.size(); ++k) {
    REQUIRE(power[k] == Approx(operating).epsilon(1e-3));
  }
}

TEST_CASE("A detuned loop that the criterion flags limit-cycles at the predicted amplitude") {
  // Adding Td = 0.5 s to the thesis' force PI: the sampled loop's G(-1) exceeds 1, and the
  // harmonic balance at the Nyquist frequency (exact for a period-2 sequence) predicts P
  // alternating between the predicted extremes.
  const PidGains gains{540.0, 1.0, 0.5};
  const auto loop = force_control_loop(gains, kappa_P, kappa_c, 0.05);
  SlsParameters mechanics{k1, 2.7, 4.3, phi0};
  const auto prediction = predict_limit_cycle(
      loop, {P_min, P_max}, equilibrium_power(0.45, 0.020, kappa_P, kappa_c, mechanics));
  REQUIRE(prediction.verdict == LoopVerdict::limit_cycle);
  const auto cycle = prediction.oscillation();
  REQUIRE(cycle.has_value());
  REQUIRE(cycle->at_nyquist);
  INFO("P* " << prediction.operating_power << " predicted P " << cycle->power_low << " / "
             << cycle->power_high << " demand " << cycle->demand_mean << " +- "
             << cycle->demand_amplitude << " stable " << cycle->stable);
  const Trace trace =
      force_loop("{proportional: 540 W/N, integral_time: 1 s, derivative_time: 0.5 s}", 120.0);
  // The last record is the end instant, where no sample is taken: compare up to the one before.
  const auto& power = trace["controller/power_command"];
  for (std::size_t k = power.size() - 200; k + 1 < power.size(); ++k) {
    const double low = std::min(power[k], power[k - 1]), high = std::max(power[k], power[k - 1]);
    REQUIRE(low == Approx(cycle->power_low).margin(1e-6));
    REQUIRE(high == Approx(cycle->power_high).margin(1e-6));
  }
}
