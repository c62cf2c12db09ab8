// The self-sensing estimator (thesis 7.2.2-7.2.3): spike filters, (7.4), the low-pass, and the
// discrete force model against the continuous plant.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include "analysis/control_tasks.h"
#include "controllers/discrete_filters.h"
#include "controllers/self_sensing_estimator.h"
#include "models/sls_mechanics.h"
#include "models/thermal_force.h"
#include "signals/piecewise_constant_signal.h"
#include "signals/piecewise_linear_signal.h"
#include "tests/support/test_components.h"
#include "tests/support/test_support.h"

using namespace tcpmsim;
using namespace tcpmsim::testing;

namespace {
constexpr double kPeriod = 0.05;  // the Muscle Drive's 20 Hz

// No spike filters and no low-pass: the deflection estimate is (7.4) of each sample.
SelfSensingEstimatorParameters unfiltered(SelfSensingEstimatorParameters p) {
  p.moving_average_length = 1;
  p.median_length = 1;
  p.low_pass_cutoff = std::numeric_limits<double>::infinity();
  return p;
}

double measure_of(const SelfSensingEstimatorParameters& p, double deflection) {
  return p.inductance(deflection, p.inductance.reference_temperature);  // (7.3)
}

}  // namespace

TEST_CASE(
    "The running median equals the median of the last N samples, its window growing at start") {
  std::mt19937_64 generator(7);
  std::uniform_int_distribution<int> coarse(0, 9);  // many ties
  for (int length : {1, 2, 5, 15}) {
    RunningMedian median(length);
    std::vector<double> history;
    for (int k = 0; k < 200; ++k) {
      const double value = coarse(generator) * 0.5;
      history.push_back(value);
      const auto first =
          history.size() > std::size_t(length) ? history.end() - length : history.begin();
      std::vector<double> window(first, history.end());
      std::sort(window.begin(), window.end());
      const std::size_t n = window.size();
      const double expected =
          n % 2 == 1 ? window[n / 2] : 0.5 * (window[n / 2 - 1] + window[n / 2]);
      REQUIRE(median.push(value) == expected);  // exact: the same two numbers are averaged
    }
  }
}

TEST_CASE("The moving average starts with the first sample and averages the last N after") {
  MovingAverage average(2);
  CHECK(average.push(4.0) == 4.0);
  CHECK(average.push(6.0) == 5.0);
  CHECK(average.push(10.0) == 8.0);
  MovingAverage three(3);
  three.push(0.3);
  three.push(0.3);
  CHECK(three.push(0.3) == 0.3);  // a constant comes out bit-exact
}

TEST_CASE("The median filter removes single spikes, and bursts up to half its window") {
  // Behind the 2-sample moving average a single spike becomes two half spikes; the 15-sample
  // median outvotes up to 7 outliers.
  const auto p = thesis_estimator_parameters();
  const double level = measure_of(p, 20e-3);
  SelfSensingEstimation estimator(p, kPeriod);
  std::vector<double> raw;
  for (int k = 0; k < 120; ++k) {
    double value = level;
    if (k == 9 || k == 30 || k == 51) value += 0.2e-6;  // single spikes up
    if (k == 70) value -= 0.3e-6;                       // and down (L* below lambda_0)
    if (k >= 90 && k < 96) value += 0.1e-6;             // a burst: 6 samples, 7 after the average
    raw.push_back(estimator.process(value, 1.0).raw_deflection);
  }
  for (int k = 0; k < 120; ++k) {
    INFO("sample " << k);
    CHECK(raw[std::size_t(k)] == Approx(20e-3).epsilon(1e-12));
  }
  // A burst longer than half the window gets through.
  SelfSensingEstimation burst(p, kPeriod);
  double last = 0.0;
  for (int k = 0; k < 40; ++k)
    last = burst.process(k >= 20 ? level + 0.1e-6 : level, 1.0).raw_deflection;
  CHECK(last < 19e-3);
  // And then it is the burst's level, inverted by (7.3): x = lambda_l / (L* - lambda_0) - lambda_x.
  const auto& law = p.inductance;
  CHECK(last ==
        Approx(law.lambda_l / (level + 0.1e-6 - law.lambda_0) - law.lambda_x).epsilon(1e-12));
}

TEST_CASE("The deflection estimate inverts (7.3) exactly on noise-free input") {
  // Tolerance: (7.4) subtracts lambda_0 from L*, losing log2(L* / (L* - lambda_0)) ~ 3 bits;
  // 1e-12 relative is a thousand times that rounding.
  const auto p = thesis_estimator_parameters();
  for (double x : {10e-3, 15e-3, 20e-3, 25e-3, 30e-3}) {
    SelfSensingEstimation estimator(p, kPeriod);
    SelfSensingEstimate estimate{};
    for (int k = 0; k < 40; ++k) estimate = estimator.process(measure_of(p, x), 1.0);
    CHECK(estimate.raw_deflection == Approx(x).epsilon(1e-12));
    CHECK(estimate.deflection == Approx(x).epsilon(1e-12));
    CHECK(estimate.velocity == Approx(0.0).margin(1e-12));
    CHECK(estimator.model_deflection(measure_of(p, x)) == Approx(x).epsilon(1e-12));
  }
  // Sample by sample, without filters, on a moving deflection.
  SelfSensingEstimation direct(unfiltered(p), kPeriod);
  for (int k = 0; k < 100; ++k) {
    const double x = 20e-3 + 8e-3 * std::sin(0.3 * k);
    CHECK(direct.process(measure_of(p, x), 1.0).deflection == Approx(x).epsilon(1e-12));
  }
}

TEST_CASE("The low-pass has -3 dB at its cut-off") {
  const double cutoff = 0.111;
  FirstOrderLowPass filter(cutoff, kPeriod);
  CHECK(filter.pole() ==
        Approx(std::exp(-2.0 * std::numbers::pi * cutoff * kPeriod)).epsilon(1e-15));
  // Drive it at the cut-off for 400 s; fit the last 20 periods (the transient, tau = 1.43 s,
  // has decayed by e^-100 by then).
  std::vector<double> time, output;
  for (int k = 0; k < 8000; ++k) {
    const double t = k * kPeriod;
    time.push_back(t);
    output.push_back(filter.push(std::sin(2.0 * std::numbers::pi * cutoff * t)));
  }
  const SineFit fit = fit_sine(time, output, cutoff, 0.0, 400.0 - 20.0 / cutoff, 400.0);
  // The fit of an exact sinusoid is exact to rounding.
  CHECK(fit.amplitude == Approx(filter.gain(cutoff)).epsilon(1e-9));
  // Against the continuous -3 dB: the step-invariant discretisation's gain at f_c is
  // (1 + theta^2/24 + O(theta^3)) / sqrt 2, theta = 2 pi f_c T = 0.0349; allow twice that term.
  const double theta = 2.0 * std::numbers::pi * cutoff * kPeriod;
  CHECK(std::abs(fit.amplitude * std::numbers::sqrt2 - 1.0) <= theta * theta / 12.0);
  CHECK(20.0 * std::log10(fit.amplitude) == Approx(-3.0103).margin(1e-3));
  // Phase: the continuous -45 degrees, the discrete form leads it by half a sample.
  CHECK(fit.phase == Approx(-std::numbers::pi / 4 + theta / 2).margin(theta * theta));
}

TEST_CASE("The low-pass reproduces the continuous step response at the sample instants") {
  FirstOrderLowPass filter(0.111, kPeriod);
  const double tau = 1.0 / (2.0 * std::numbers::pi * 0.111);
  filter.push(0.0);  // at rest
  for (int k = 1; k <= 200; ++k) {
    // The sample at t_k holds the input over (t_{k-1}, t_k]: a unit step just after t_0.
    CHECK(filter.push(1.0) == Approx(1.0 - std::exp(-k * kPeriod / tau)).epsilon(1e-13));
  }
}

TEST_CASE("The discrete thermal force (7.1) and SLS (7.6) equal their analytic responses") {
  const auto p = thesis_estimator_parameters();
  // F_T from rest under constant power: (kappa_P P / kappa_c)(1 - exp(-kappa_c t)).
  DiscreteThermalForce thermal(p.heating_gain, p.cooling_rate, kPeriod);
  thermal.reset(0.0);
  for (int k = 1; k <= 400; ++k) {
    const double expected =
        p.heating_gain * 2.0 / p.cooling_rate * (1.0 - std::exp(-p.cooling_rate * k * kPeriod));
    REQUIRE(thermal.advance(2.0) == Approx(expected).epsilon(1e-12));
  }
  // SLS from rest under a ramp x = x0 + v t: F_l = k1 x + c v (1 - exp(-k2 t / c)), the dashpot
  // stretching towards v c / k2.
  const auto& m = p.mechanics;
  DiscreteSls sls(m, kPeriod);
  const double x0 = 15e-3, v = 1e-3;
  sls.reset(x0);
  CHECK(sls.value() == Approx(m.k1 * x0));
  for (int k = 1; k <= 400; ++k) {
    const double t = k * kPeriod, x = x0 + v * t;
    const double expected = m.k1 * x + m.damping * v * (1.0 - std::exp(-m.k2 / m.damping * t));
    REQUIRE(sls.advance(x, v) == Approx(expected).epsilon(1e-12));
  }
  // After a long ramp: F_l = k1 x + c v exactly, the steady viscous force.
  CHECK(sls.value() - m.k1 * (x0 + v * 400 * kPeriod) == Approx(m.damping * v).epsilon(1e-5));
}

TEST_CASE("The discrete force model matches the continuous plant at the sample instants") {
  // The plant (ReducedThermalForce, SlsMechanics) runs through the engine with the same
  // parameters as the estimator, a power stepping at sample instants and a deflection
  // piecewise linear between sample instants. The estimator, without filters, must give the
  // plant's F, F_T and x at every sample, to the solver's accuracy.
  const auto p = unfiltered(thesis_estimator_parameters());
  SystemBuilder system;
  system.add(std::make_unique<SignalSource>(
      "power", std::make_unique<PiecewiseConstantSignal>(1.0, std::vector<double>{2.0, 5.0, 8.5},
                                                         std::vector<double>{3.0, 0.1, 2.2})));
  system.add(std::make_unique<SignalSource>(
      "imposed", std::make_unique<PiecewiseLinearSignal>(
                     std::vector<double>{0.0, 1.0, 3.0, 3.5, 6.0, 10.0},
                     std::vector<double>{20e-3, 20e-3, 25e-3, 15e-3, 15e-3, 22e-3})));
  ReducedThermalForceParameters thermal;
  thermal.heating_gain = p.heating_gain;
  thermal.cooling_rate = p.cooling_rate;
  thermal.ambient_temperature = 296.15;
  auto& heating = system.add(std::make_unique<ReducedThermalForce>("muscle", thermal));
  auto& mechanics = system.add(std::make_unique<SlsMechanics>("muscle", p.mechanics));
  auto& sensor = system.add(std::make_unique<DecayTimeSensor>(p.inductance));
  auto& estimator = system.add(std::make_unique<SelfSensingEstimator>("estimator", p, kPeriod));
  system.connect(heating, "power", "power.value");
  system.connect(mechanics, "thermal_force", "muscle.thermal_force");
  system.connect(mechanics, "deflection", "imposed.value");
  system.connect(sensor, "deflection", "muscle.deflection");
  system.connect(estimator, "inductance_measure", "sensor.inductance_measure");
  system.connect(estimator, "power_command", "power.value");
  const auto assembled = system.build();
  SolverSettings settings;
  settings.relative_tolerance = 1e-10;
  Context context(*assembled);
  Integrator integrator(*assembled, context, settings);
  MemorySink sink(*assembled);
  integrator.run(0.0, 10.0, kPeriod, sink);

  // Forces are below 0.6 N.
  const double allowed_force = allowed(1e-10, 0.6);
  double worst_force = 0.0, worst_thermal = 0.0, worst_deflection = 0.0;
  for (std::size_t i = 0; i + 1 < sink.time.size(); ++i) {  // the end is not a sample instant
    worst_force =
        std::max(worst_force, std::abs(sink["estimator/force"][i] - sink["muscle/force"][i]));
    worst_thermal = std::max(worst_thermal, std::abs(sink["estimator/thermal_force"][i] -
                                                     sink["muscle/thermal_force"][i]));
    worst_deflection = std::max(
        worst_deflection, std::abs(sink["estimator/deflection"][i] - sink["muscle/deflection"][i]));
  }
  INFO("worst differences: F " << worst_force << " N, F_T " << worst_thermal << " N, x "
                               << worst_deflection << " m");
  CHECK(worst_force <= allowed_force);
  CHECK(worst_thermal <= allowed_force);
  CHECK(worst_deflection <= 1e-12 * 30e-3);  // (7.4) of (7.3): rounding only, as above
  CHECK(sink.time.size() == 201);
  // The force moved: the comparison is not between two constants.
  const auto [low, high] =
      std::minmax_element(sink["muscle/force"].begin(), sink["muscle/force"].end());
  CHECK(*high - *low > 0.1);
}

TEST_CASE("Before the first usable L* the deflection and force are unknown; F_T is not") {
  const auto p = thesis_estimator_parameters();
  SelfSensingEstimation estimator(p, kPeriod);
  DiscreteThermalForce thermal(p.heating_gain, p.cooling_rate, kPeriod);
  // The Muscle Drive reports 0 before its first off-phase.
  auto estimate = estimator.process(0.0, 2.0);
  CHECK(std::isnan(estimate.deflection));
  CHECK(std::isnan(estimate.force));
  CHECK(std::isnan(estimate.velocity));
  CHECK(estimate.thermal_force == 0.0);  // initial_thermal_force; the power acts from now on
  estimate = estimator.process(std::numeric_limits<double>::quiet_NaN(), 2.0);
  CHECK(estimate.thermal_force == Approx(thermal.gain() * 2.0).epsilon(1e-15));
  CHECK(estimator.rejected_measurements() == 2);
  // The first usable sample starts the deflection chain, relaxed: F = k1 x + F_T + phi_0.
  estimate = estimator.process(measure_of(p, 20e-3), 2.0);
  const double f_t = thermal.gain() * 2.0 * (1.0 + thermal.decay());
  CHECK(estimate.thermal_force == Approx(f_t).epsilon(1e-14));
  CHECK(estimate.deflection == Approx(20e-3).epsilon(1e-12));
  CHECK(estimate.velocity == 0.0);
  CHECK(estimate.force ==
        Approx(p.mechanics.k1 * 20e-3 + f_t + p.mechanics.force_offset).epsilon(1e-12));
  // A filtered L* at or below lambda_0 holds the last deflection; it is counted.
  SelfSensingEstimation bare(unfiltered(p), kPeriod);
  bare.process(measure_of(p, 20e-3), 1.0);
  const auto held = bare.process(0.9 * p.inductance.lambda_0, 1.0);
  CHECK(held.raw_deflection == Approx(20e-3).epsilon(1e-12));
  CHECK(bare.out_of_domain_samples() == 1);
}

TEST_CASE("Calibration offsets add to deflection and force without a velocity impulse") {
  const auto p = thesis_estimator_parameters();
  SelfSensingEstimation estimator(p, kPeriod);
  const double level = measure_of(p, 20e-3);
  for (int k = 0; k < 40; ++k) estimator.process(level, 1.0);
  const auto before = estimator.estimate();
  estimator.set_force_offset(5e-3);
  CHECK(estimator.estimate().force == Approx(before.force + 5e-3).epsilon(1e-14));
  estimator.set_deflection_offset(-1e-3);
  CHECK(estimator.estimate().deflection == Approx(19e-3).epsilon(1e-12));
  CHECK(estimator.estimate().raw_deflection == Approx(19e-3).epsilon(1e-12));
  const auto after = estimator.process(level, 1.0);
  CHECK(after.velocity == Approx(0.0).margin(1e-15));
  // F_l follows the calibrated deflection with the SLS's relaxation, (1 - phi) per sample.
  DiscreteSls sls(p.mechanics, kPeriod);
  const double expected_step = (1.0 - sls.decay()) * p.mechanics.k1 * -1e-3;
  const double thermal_step = after.thermal_force - before.thermal_force;
  CHECK(after.force - before.force - 5e-3 - thermal_step == Approx(expected_step).epsilon(1e-6));
}

TEST_CASE("The estimator reads its parameters with units, L* in seconds") {
  const ConfigNode root = ConfigNode::load_text(R"(
estimator:
  inductance: {lambda_l: 2.81 us*mm, lambda_x: 28.8 mm, lambda_0: 0.433 us}
  filters: {moving_average: 3, median: 9, low_pass_cutoff: 0.2 Hz}
  thermal: {kappa_P: 7.2e-3 N/J, kappa_c: 131.6e-3 1/s}
  mechanics: {k1: 10.8e-3 N/mm, k2: 2.7e-3 N/mm, damping: 4.3e-3 N*s/mm, force_offset: 106.9e-3 N}
  calibration: {deflection_offset: -0.27 mm}
)",
                                                "estimator.yaml", {}, shared_units());
  const auto estimator = SelfSensingEstimator::from_config("estimator", root.at("estimator"), 0.05);
  root.reject_unknown_keys();
  const auto& p = estimator->defaults();
  CHECK(p.inductance.lambda_l == Approx(2.81e-9));
  CHECK(p.inductance.lambda_x == Approx(28.8e-3));
  CHECK(p.inductance.lambda_0 == Approx(0.433e-6));
  CHECK(p.moving_average_length == 3);
  CHECK(p.median_length == 9);
  CHECK(p.low_pass_cutoff == Approx(0.2));
  CHECK(p.heating_gain == Approx(7.2e-3));
  CHECK(p.cooling_rate == Approx(0.1316));
  CHECK(p.initial_thermal_force == 0.0);
  CHECK(p.mechanics.k1 == Approx(10.8));
  CHECK(p.mechanics.damping == Approx(4.3));
  CHECK(p.deflection_offset == Approx(-0.27e-3));
  CHECK(p.force_offset == 0.0);
  CHECK(estimator->period() == 0.05);
  CHECK(estimator->sampling_stage() == Component::SamplingStage::estimator);

  auto error_of = [](const std::string& yaml) {
    try {
      const ConfigNode node = ConfigNode::load_text(yaml, "e.yaml", {}, shared_units());
      SelfSensingEstimator::from_config("estimator", node.at("estimator"), 0.05);
      node.reject_unknown_keys();
    } catch (const ConfigError& error) {
      return std::string(error.what());
    }
    return std::string("no error");
  };
  const std::string base = R"(
estimator:
  inductance: {lambda_l: 2.81 us*mm, lambda_x: 28.8 mm, lambda_0: 0.433 us}
  thermal: {kappa_P: 7.2e-3 N/J, kappa_c: 131.6e-3 1/s}
  mechanics: {k1: 10.8e-3 N/mm, k2: 2.7e-3 N/mm, damping: 4.3e-3 N*s/mm, force_offset: 0.1 N}
)";
  CHECK(error_of(base) == "no error");
  CHECK_THAT(error_of(base + "  filters: {median: 0}\n"),
             Catch::Contains(
                 "estimator.filters.median: expected an integer, a value in [1, 10000], got '0'"));
  CHECK_THAT(error_of(base + "  filters: {lowpass_cutoff: 1 Hz}\n"),
             Catch::Contains("unknown key 'lowpass_cutoff' (did you mean 'low_pass_cutoff'?)"));
  std::string dimensionless = base;
  dimensionless.replace(dimensionless.find("0.433 us"), 8, "0.433");
  CHECK_THAT(error_of(dimensionless), Catch::Contains("estimator.inductance.lambda_0"));
}
