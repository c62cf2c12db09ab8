// The control-task references and their analysis (thesis 7.3.4, 7.3.6, 7.4): rise times,
// sine fits, Bode points, the -3 dB bandwidth and estimation-error statistics.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <numeric>
#include <random>

#include "analysis/control_tasks.h"
#include "analysis/statistics.h"
#include "signals/control_task_signals.h"

using namespace tcpmsim;

namespace {
constexpr double kLow = 3.9810717055349725e-3, kHigh = 7.9432823472428138e-2;  // 10^-2.4, 10^-1.1

// The exact response of the first-order lag 1/(1 + tau s) to a piecewise-constant reference,
// sampled every dt.
struct Series {
  std::vector<double> time, reference, response;
};
Series first_order_steps(const Signal& reference, double tau, double end, double dt) {
  Series series;
  double state = reference.value(0.0), previous_time = 0.0;
  for (long k = 0; k * dt < end - 1e-9; ++k) {
    const double t = k * dt;
    // Exact between samples: the reference is constant on [previous, t) (steps on the grid).
    state = reference.value(previous_time) +
            (state - reference.value(previous_time)) * std::exp(-(t - previous_time) / tau);
    previous_time = t;
    series.time.push_back(t);
    series.reference.push_back(reference.value(t));
    series.response.push_back(state);
  }
  return series;
}
}  // namespace

TEST_CASE("Rise times of a first-order response equal tau ln 9 (10-90 %), steps up and down") {
  StepSequenceSettings steps;
  steps.low = 10e-3;
  steps.high = 30e-3;
  steps.start_time = 20.0;
  const auto reference = make_step_sequence(steps);
  const double tau = 2.0, dt = 0.01;
  const Series s = first_order_steps(*reference, tau, 160.0, dt);
  const auto rises = step_rise_times(s.time, s.reference, s.response);
  REQUIRE(rises.size() == 7);
  // Linear interpolation of an exponential between samples misplaces a crossing by at most
  // dt^2 / (8 tau) = 6.3e-6 s; two crossings per rise time.
  const double tolerance = 2.0 * dt * dt / (8.0 * tau);
  for (const auto& rise : rises) {
    INFO("step at " << rise.step_time << " s to " << rise.target);
    CHECK(rise.reached);
    CHECK(rise.rise_time == Approx(tau * std::log(9.0)).margin(tolerance));
    CHECK(rise.hold == Approx(20.0).margin(1e-9));
  }
  CHECK(rises[0].step_time == Approx(20.0).margin(1e-9));
  CHECK(rises[0].target == Approx(10e-3));
  CHECK(rises[1].target == Approx(30e-3));
  // Measured from the step to 90 %: tau ln 10.
  const auto from_step = step_rise_times(s.time, s.reference, s.response, {0.0, 0.9});
  CHECK(from_step[3].rise_time == Approx(tau * std::log(10.0)).margin(tolerance));
}

TEST_CASE("A step whose response never reaches its level is charged the whole hold") {
  // The thesis' outliers at 20 s: a first-order response never reaches 100 % of the step.
  StepSequenceSettings steps;
  steps.low = 0.375;
  steps.high = 0.525;
  const auto reference = make_step_sequence(steps);
  const Series s = first_order_steps(*reference, 1.0, 140.0, 0.05);
  const auto rises = step_rise_times(s.time, s.reference, s.response, {0.0, 1.0});
  REQUIRE(rises.size() == 6);  // the first level holds from t = 0: no step into it
  for (const auto& rise : rises) {
    CHECK_FALSE(rise.reached);
    CHECK(std::isnan(rise.upper_time));
    CHECK(rise.rise_time == Approx(20.0).margin(1e-9));
    CHECK(rise.lower_time == rise.step_time);  // 0 % is the step itself
  }
  // A response stuck at 80 % (a saturated actuator) fails the 90 % level too.
  std::vector<double> time, reference_values, response;
  for (int k = 0; k < 400; ++k) {
    time.push_back(k * 0.1);
    reference_values.push_back(k < 100 ? 0.0 : 1.0);
    response.push_back(k < 100 ? 0.0 : std::min(0.8, 0.1 * (k - 100)));
  }
  const auto stuck = step_rise_times(time, reference_values, response);
  REQUIRE(stuck.size() == 1);
  CHECK_FALSE(stuck[0].reached);
  CHECK(stuck[0].lower_time == Approx(10.1).margin(1e-9));
  CHECK(stuck[0].rise_time == Approx(30.0).margin(1e-9));  // 10 s to 40 s (one sample past)
}

TEST_CASE("A least-squares sine fit recovers amplitude, phase and offset") {
  std::vector<double> time, values;
  const double f = 0.03, origin = 12.0;
  for (int k = 0; k < 2000; ++k) {
    const double t = k / 16.0;  // the thesis' 16 Hz resampling
    time.push_back(t);
    values.push_back(0.4 + 0.05 * std::sin(2.0 * std::numbers::pi * f * (t - origin) - 2.5));
  }
  const SineFit fit = fit_sine(time, values, f, origin, 30.0, 30.0 + 2.0 / f);
  CHECK(fit.amplitude == Approx(0.05).epsilon(1e-12));
  CHECK(fit.phase == Approx(-2.5).margin(1e-12));
  CHECK(fit.offset == Approx(0.4).epsilon(1e-12));
  CHECK(fit.rms_residual < 1e-14);
  CHECK(fit.samples == 1067);  // t in [30, 96.67)
  CHECK_THROWS_AS(fit_sine(time, values, f, origin, 200.0, 300.0), std::invalid_argument);
}

TEST_CASE("Bode points and the -3 dB bandwidth of a first-order lag equal 1/(2 pi tau)") {
  // The thesis' sweep, 5 mm around 20 mm, and the lag's exact steady-state response at each
  // frequency (so the fits are exact and the test pins the interpolation, not a transient).
  SineSweepSettings settings;
  settings.offset = 20e-3;
  settings.amplitude = 5e-3;
  const auto sweep = make_stepped_sine_sweep(settings);
  const auto& schedule = sweep->schedule();
  for (double bandwidth : {0.039, 0.056, 0.0123}) {
    const double tau = 1.0 / (2.0 * std::numbers::pi * bandwidth);
    std::vector<double> time, reference, response;
    for (double t = 0.0; t < sweep->end_time(); t += 1.0 / 16.0) {
      time.push_back(t);
      reference.push_back(sweep->value(t));
      std::size_t i = 0;
      while (i + 1 < schedule.start_times.size() && t >= schedule.start_times[i + 1]) ++i;
      const double omega = 2.0 * std::numbers::pi * schedule.frequencies[i];
      const double gain = 1.0 / std::hypot(1.0, omega * tau), lag = std::atan(omega * tau);
      response.push_back(settings.offset +
                         settings.amplitude * gain *
                             std::sin(omega * (t - schedule.start_times[i]) - lag));
    }
    const auto points = sweep_frequency_response(time, reference, response, schedule);
    REQUIRE(points.size() == 15);
    for (const auto& point : points) {
      const double omega_tau = 2.0 * std::numbers::pi * point.frequency * tau;
      CHECK(point.magnitude == Approx(1.0 / std::hypot(1.0, omega_tau)).epsilon(1e-9));
      CHECK(point.phase == Approx(-std::atan(omega_tau)).margin(1e-9));
      CHECK(point.response.offset == Approx(settings.offset).epsilon(1e-9));
    }
    const auto found = bandwidth_3db(points);
    REQUIRE(found.has_value());
    // Exactly the linear interpolation (dB against log10 f) between the bracketing points:
    const double level = -10.0 * std::log10(2.0);
    std::size_t j = 0;
    while (points[j].magnitude_db > level) ++j;
    const double x0 = std::log10(points[j - 1].frequency), x1 = std::log10(points[j].frequency);
    const double expected =
        std::pow(10.0, x0 + (level - points[j - 1].magnitude_db) /
                                (points[j].magnitude_db - points[j - 1].magnitude_db) * (x1 - x0));
    CHECK(*found == Approx(expected).epsilon(1e-12));
    // Against the analytic 1/(2 pi tau): in u = ln f the lag's dB curve -10 log10(1 + e^(2v))
    // (v = u - ln f_c) has |d2/du2| <= 10/ln 10, so the chord between points h = ln(f_{i+1}/f_i)
    // = 0.2138 apart misses it by at most h^2/8 * 10/ln 10 = 0.0248 dB. Over a bracketing
    // interval the slope is at least (20/ln 10) e^-h/(1 + e^-h) = 3.42 dB per unit of u, so the
    // crossing moves by at most 0.0248/3.42 = 0.0073 in ln f.
    CHECK(*found == Approx(bandwidth).epsilon(0.0073));
  }
  // No crossing inside the sweep: no bandwidth.
  std::vector<FrequencyResponsePoint> flat(3);
  for (std::size_t i = 0; i < 3; ++i)
    flat[i].frequency = 0.01 * (i + 1), flat[i].magnitude_db = -1.0;
  CHECK_FALSE(bandwidth_3db(flat).has_value());
  flat[0].magnitude_db = -4.0;
  CHECK_FALSE(bandwidth_3db(flat).has_value());  // below -3 dB from the start
}

TEST_CASE("Only the last two periods of each frequency enter the sweep fits") {
  SineSweepSettings settings;
  settings.offset = 0.4;
  settings.amplitude = 0.05;
  settings.frequencies = 4;
  const auto sweep = make_stepped_sine_sweep(settings);
  const auto& schedule = sweep->schedule();
  std::vector<double> time, reference, response;
  for (double t = 0.0; t < sweep->end_time(); t += 0.05) {
    time.push_back(t);
    reference.push_back(sweep->value(t));
    // Half the amplitude in the last two periods; garbage in the first (a transient).
    std::size_t i = 0;
    while (i + 1 < schedule.start_times.size() && t >= schedule.start_times[i + 1]) ++i;
    const bool first_period = t < schedule.start_times[i] + 1.0 / schedule.frequencies[i];
    response.push_back(first_period ? 7.0 : 0.4 + 0.5 * (sweep->value(t) - 0.4));
  }
  for (const auto& point : sweep_frequency_response(time, reference, response, schedule)) {
    CHECK(point.magnitude == Approx(0.5).epsilon(1e-9));
    CHECK(point.phase == Approx(0.0).margin(1e-9));
  }
}

TEST_CASE(
    "The stepped sine sweep runs 15 log-spaced frequencies of the thesis band, 3 periods each") {
  SineSweepSettings settings;
  settings.offset = 20e-3;
  settings.amplitude = 5e-3;
  settings.start_time = 10.0;
  const auto sweep = make_stepped_sine_sweep(settings);
  const auto& s = sweep->schedule();
  REQUIRE(s.frequencies.size() == 15);
  CHECK(s.frequencies.front() == Approx(kLow).epsilon(1e-14));
  CHECK(s.frequencies.back() == Approx(kHigh).epsilon(1e-14));
  double total = 0.0;
  for (std::size_t i = 0; i < 15; ++i) {
    if (i > 0) {
      CHECK(s.frequencies[i] / s.frequencies[i - 1] == Approx(std::pow(kHigh / kLow, 1.0 / 14)));
      CHECK(s.start_times[i] == s.end_time(i - 1));  // contiguous
    }
    total += 3.0 / s.frequencies[i];
    // Continuous at the boundaries (each frequency starts at zero phase), a breakpoint there.
    CHECK(sweep->value(s.start_times[i]) == Approx(20e-3).epsilon(1e-12));
    CHECK(sweep->value(s.end_time(i) - 1e-9) == Approx(20e-3).margin(1e-10));
    CHECK(sweep->next_breakpoint_after(s.start_times[i] + 1e-6) == s.end_time(i));
    CHECK(sweep->slope(s.start_times[i]) ==
          Approx(5e-3 * 2.0 * std::numbers::pi * s.frequencies[i]).epsilon(1e-12));
  }
  CHECK(sweep->end_time() - 10.0 == Approx(total).epsilon(1e-12));
  CHECK(total == Approx(3756.0).epsilon(1e-3));
  CHECK(sweep->value(0.0) == 20e-3);
  CHECK(sweep->value(sweep->end_time() + 1.0) == 20e-3);
  CHECK(sweep->next_breakpoint_after(0.0) == 10.0);
  CHECK(sweep->next_breakpoint_after(sweep->end_time()) == kNoBreakpoint);
  // A quarter period into the first frequency: the crest.
  CHECK(sweep->value(10.0 + 0.25 / kLow) == Approx(25e-3).epsilon(1e-12));
  const auto [low, high] = sweep->range(0.0, 1e5);
  CHECK(low == Approx(15e-3));
  CHECK(high == Approx(25e-3));
  const auto [before_low, before_high] = sweep->range(0.0, 9.0);
  CHECK(before_low == 20e-3);
  CHECK(before_high == 20e-3);
  const auto [rise_low, rise_high] = sweep->range(10.0, 10.0 + 0.1 / kLow);  // rising part only
  CHECK(rise_low == Approx(20e-3));
  CHECK(rise_high == Approx(20e-3 + 5e-3 * std::sin(0.2 * std::numbers::pi)));
  const auto description = sweep->describe();
  CHECK(description.type == "stepped_sine");
  REQUIRE(description.arrays.size() == 2);
  CHECK(description.arrays[0].second == s.frequencies);
}

TEST_CASE("The step sequence visits seven levels from the outside in, each held 20 s") {
  StepSequenceSettings settings;
  settings.low = 10e-3;
  settings.high = 30e-3;
  settings.start_time = 20.0;
  const auto sequence = make_step_sequence(settings);
  const std::vector<double> expected{10e-3,     30e-3,     40e-3 / 3, 80e-3 / 3,
                                     50e-3 / 3, 70e-3 / 3, 20e-3};
  CHECK(sequence->value(19.99) == Approx(20e-3));  // the initial value: mid-range
  for (std::size_t j = 0; j < 7; ++j) {
    CHECK(sequence->value(20.0 + 20.0 * j) == Approx(expected[j]).epsilon(1e-12));
    CHECK(sequence->value(39.99 + 20.0 * j) == Approx(expected[j]).epsilon(1e-12));
  }
  CHECK(sequence->value(1e4) == Approx(20e-3));
  CHECK(sequence->times().size() == 7);
  // Step sizes after the first: 6, 5, 4, 3, 2, 1 sixths of the range.
  const auto levels = step_sequence_levels(0.0, 6.0, 7);
  for (std::size_t j = 1; j < 7; ++j) CHECK(std::abs(levels[j] - levels[j - 1]) == Approx(7.0 - j));
  CHECK(sequence->describe().type == "step_sequence");
}

TEST_CASE("Estimation-error statistics of synthetic Gaussian errors recover mean and 95 % band") {
  // The thesis' deflection error: -0.27 mm mean, 95 % of errors within +-2.14 mm.
  const double mean = -0.27e-3, sigma = 2.14e-3 / 1.959963984540054;
  const std::size_t n = 200000;
  std::mt19937_64 generator(2019);
  std::normal_distribution<double> noise(mean, sigma);
  std::vector<double> truth(n), estimate(n);
  for (std::size_t i = 0; i < n; ++i) {
    truth[i] = 20e-3 + 5e-3 * std::sin(0.001 * double(i));
    estimate[i] = truth[i] + noise(generator);
  }
  const auto stats = estimation_error_statistics(truth, estimate);
  CHECK(stats.count == n);
  // Four standard errors: sigma/sqrt(n) for the mean, sigma/sqrt(2n) for sigma, and
  // sqrt(p(1-p)/n)/phi(z) sigma = 0.00845 sigma for the 2.5 % and 97.5 % quantiles.
  const double root_n = std::sqrt(double(n));
  CHECK(stats.mean == Approx(mean).margin(4.0 * sigma / root_n));
  CHECK(stats.standard_deviation == Approx(sigma).margin(4.0 * sigma / std::sqrt(2.0 * n)));
  CHECK(stats.half_width_95 == Approx(2.14e-3).margin(1.96 * 4.0 * sigma / std::sqrt(2.0 * n)));
  const double quantile_error = 4.0 * std::sqrt(0.025 * 0.975 / n) / 0.05844 * sigma;
  CHECK(stats.percentile_2_5 == Approx(mean - 2.14e-3).margin(quantile_error));
  CHECK(stats.percentile_97_5 == Approx(mean + 2.14e-3).margin(quantile_error));
  CHECK(stats.rmse == Approx(std::hypot(mean, sigma)).epsilon(4.0 / root_n));
  // Error = estimate - truth: an underestimate has a negative mean.
  CHECK(calibration_offset(truth, estimate) == Approx(-stats.mean).epsilon(1e-9));
}

TEST_CASE("Error statistics, percentiles, R^2 and calibration offsets on small exact data") {
  const std::vector<double> truth{0.0, 0.0, 0.0, 0.0}, estimate{1.0, 2.0, 3.0, 4.0};
  const auto stats = estimation_error_statistics(truth, estimate);
  CHECK(stats.mean == 2.5);
  CHECK(stats.standard_deviation == Approx(std::sqrt(5.0 / 3.0)).epsilon(1e-15));
  CHECK(stats.half_width_95 == Approx(1.959963984540054 * std::sqrt(5.0 / 3.0)).epsilon(1e-15));
  CHECK(stats.rmse == Approx(std::sqrt(7.5)).epsilon(1e-15));
  // Order statistics 1, 2, 3, 4 at positions 0..3; p = 2.5 % sits at 0.075, 97.5 % at 2.925.
  CHECK(stats.percentile_2_5 == Approx(1.075).epsilon(1e-15));
  CHECK(stats.percentile_97_5 == Approx(3.925).epsilon(1e-15));
  CHECK(analysis::percentile({5.0, 1.0, 3.0}, 50.0) == 3.0);
  CHECK(analysis::percentile({5.0, 1.0, 3.0}, 100.0) == 5.0);
  // (7.15): truth 1, 2, 3, 4 (mean 2.5, total 5) against 1, 2, 3, 5 (residual 1).
  CHECK(analysis::r_squared(std::vector<double>{1, 2, 3, 4}, std::vector<double>{1, 2, 3, 5}) ==
        Approx(0.8).epsilon(1e-15));
  CHECK(calibration_offset(std::vector<double>{20e-3, 20e-3},
                           std::vector<double>{20.5e-3, 20.3e-3}) ==
        Approx(-0.4e-3).epsilon(1e-12));
  CHECK_THROWS_AS(estimation_error_statistics(truth, std::vector<double>{1.0, NAN, 3.0, 4.0}),
                  std::invalid_argument);
}
