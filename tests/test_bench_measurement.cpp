// Synthetic measurements: a scenario read by a bench's instruments, with the noise, resolution
// and spikes they are declared with, reproducibly.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "identification/bench_measurement.h"
#include "identification/fit_problem.h"
#include "sim/io/measured_data.h"
#include "sim/run.h"
#include "tests/support/test_support.h"

using namespace tcpmsim;
using namespace tcpmsim::testing;

namespace {

std::filesystem::path bench_directory() {
  return process_directory("bench");
}

// The test muscle heated by a power staircase for 1000 s at 10 Hz: 10001 samples.
Scenario staircase_muscle() {
  return scenario_from_text(replaced(physical_muscle_yaml(), "power: 0 W",
                                     "power: {type: steps, initial: 0 W, times: [100 s, 400 s], "
                                     "values: [1 W, 0.3 W]}"),
                            {"scenario.duration=1000 s"});
}

fit::Bench bench_from(const std::string& text, const Scenario& scenario) {
  const auto path = bench_directory() / "bench.yaml";
  std::ofstream(path) << text;
  return fit::load_bench(path.string(), scenario, shared_units());
}

std::string bench_error(const std::string& text, const Scenario& scenario) {
  try {
    bench_from(text, scenario);
  } catch (const ConfigError& error) {
    return error.what();
  }
  return "no error";
}

}  // namespace

TEST_CASE("A bench's instruments add their declared noise, resolution and spikes, and no more") {
  const Scenario scenario = staircase_muscle();
  fit::OutputPicker clean(*scenario.system, {"drive.power", "load.force", "muscle.temperature"});
  integrate(scenario, clean);
  const fit::Bench bench = bench_from(R"(seed: 4
channels:
  - {channel: power, output: drive.power, unit: mW}
  - {channel: force, output: load.force, unit: mN, noise: 2 mN}
  - {channel: temperature, output: muscle.temperature, unit: degC, resolution: 0.1 K,
     spikes: {probability: 0.01, size: 5 K}}
)",
                                      scenario);
  const std::string text = fit::measure(scenario, bench, *shared_units());
  const MeasuredData data = parse_measured_csv(text, "bench.csv", *shared_units());
  const std::size_t n = clean.times.size();
  REQUIRE(data.time().size() == n);
  CHECK(bitwise_equal(data.time(), clean.times));

  // An instrument without noise reads the output itself (to the 17 digits written).
  CHECK(max_abs_difference(data.find("power")->values, clean.values[0]) <= 1e-15);

  // Noise: mean 0 and the declared standard deviation, to their sampling errors.
  double sum = 0.0, squares = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double error = data.find("force")->values[i] - clean.values[1][i];
    sum += error;
    squares += error * error;
  }
  const double mean = sum / double(n);
  const double deviation = std::sqrt(squares / double(n) - mean * mean);
  CHECK(std::abs(mean) < 4.0 * 2e-3 / std::sqrt(double(n)));
  CHECK(deviation == Approx(2e-3).epsilon(4.0 / std::sqrt(2.0 * double(n))));

  // Resolution: every reading a multiple of 0.1 K; spikes: +-5 K in about 1 % of the samples.
  std::size_t spikes = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double reading = data.find("temperature")->values[i];
    CHECK(std::abs(reading / 0.1 - std::round(reading / 0.1)) < 1e-6);
    const double error = reading - clean.values[2][i];
    if (std::abs(error) > 2.5) {
      ++spikes;
      CHECK(std::abs(std::abs(error) - 5.0) <= 0.05 + 1e-9);
    } else {
      CHECK(std::abs(error) <= 0.05 + 1e-9);
    }
  }
  const double expected = 0.01 * double(n);
  CHECK(std::abs(double(spikes) - expected) < 4.0 * std::sqrt(expected));
}

TEST_CASE(
    "A correlated noise is first-order: its size, correlation time, and the white part kept") {
  const Scenario scenario = staircase_muscle();
  fit::OutputPicker clean(*scenario.system, {"load.force"});
  integrate(scenario, clean);
  const auto measured = [&](const std::string& force) {
    return parse_measured_csv(
        fit::measure(scenario, bench_from("seed: 3\nchannels:\n" + force, scenario),
                     *shared_units()),
        "bench.csv", *shared_units());
  };
  const MeasuredData white =
      measured("  - {channel: force, output: load.force, unit: mN, noise: 1 mN}\n");
  const MeasuredData both = measured(
      "  - {channel: force, output: load.force, unit: mN, noise: 1 mN,\n"
      "     correlated_noise: {size: 2 mN, correlation_time: 0.5 s}}\n");
  // The correlated part alone: both readings less the white ones (the same draws, from the
  // instrument's own stream).
  const std::size_t n = clean.times.size();
  std::vector<double> part(n);
  for (std::size_t i = 0; i < n; ++i)
    part[i] = both.find("force")->values[i] - white.find("force")->values[i];
  double squares = 0.0;
  for (const double e : part) squares += e * e;
  // 10001 samples 0.1 s apart with tau = 0.5 s: about n / (2 tau / dt) = 1000 independent ones.
  const double effective = double(n) * (1 - std::exp(-0.2)) / (1 + std::exp(-0.2));
  CHECK(std::sqrt(squares / double(n)) == Approx(2e-3).epsilon(4.0 / std::sqrt(2.0 * effective)));
  // Its autocorrelation at lags of 1, 2 and 5 samples is exp(-k dt / tau).
  for (const int lag : {1, 2, 5}) {
    double product = 0.0;
    for (std::size_t i = static_cast<std::size_t>(lag); i < n; ++i)
      product += part[i] * part[i - static_cast<std::size_t>(lag)];
    const double correlation = product / squares;
    INFO("lag " << lag);
    CHECK(correlation == Approx(std::exp(-0.1 * lag / 0.5)).margin(4.0 / std::sqrt(effective)));
  }
  CHECK_THAT(
      bench_error("channels:\n  - {channel: force, output: load.force, unit: N, "
                  "correlated_noise: {size: 1 mN}}\n",
                  scenario),
      Catch::EndsWith("bench.yaml:2:69: error: channels[0].correlated_noise: missing required key "
                      "'correlation_time'"));
}

TEST_CASE("A synthetic measurement is the same for the same seed, and each channel draws alone") {
  const Scenario scenario = staircase_muscle();
  const std::string force = "  - {channel: force, output: load.force, unit: N, noise: 1 mN}\n";
  const std::string temperature =
      "  - {channel: temperature, output: muscle.temperature, unit: K, noise: 0.1 K}\n";
  const auto measured = [&](const std::string& seed, const std::string& channels) {
    return parse_measured_csv(
        fit::measure(scenario, bench_from("seed: " + seed + "\nchannels:\n" + channels, scenario),
                     *shared_units()),
        "bench.csv", *shared_units());
  };
  const MeasuredData first = measured("1", force);
  CHECK(bitwise_equal(measured("1", force).find("force")->values, first.find("force")->values));
  CHECK(max_abs_difference(measured("2", force).find("force")->values,
                           first.find("force")->values) > 1e-4);
  // Another instrument on the bench leaves the force's noise as it was.
  CHECK(bitwise_equal(measured("1", temperature + force).find("force")->values,
                      first.find("force")->values));
  // A noise is a difference: 0.1 degC is 0.1 K (not 273.25 K), the same draws.
  CHECK(bitwise_equal(measured("1", replaced(temperature, "noise: 0.1 K", "noise: 0.1 degC"))
                          .find("temperature")
                          ->values,
                      measured("1", temperature).find("temperature")->values));
}

TEST_CASE("A bench file's mistakes are located at their keys") {
  const Scenario scenario = staircase_muscle();
  const std::string file = (bench_directory() / "bench.yaml").string();
  CHECK(bench_error("channels:\n  - {channel: forse, output: load.force, unit: N}\n", scenario) ==
        file +
            ":2:15: error: channels[0].channel: expected a measured quantity (power, "
            "deflection, force, decay_time, ...; left.force for an instance), got 'forse'");
  CHECK(bench_error("channels:\n  - {channel: force, output: load.forse, unit: N}\n", scenario) ==
        file +
            ":2:30: error: channels[0].output: the scenario has no output 'load.forse' "
            "(outputs are named group.name, as in its record)");
  CHECK(bench_error("channels:\n  - {channel: force, output: drive.power, unit: N}\n", scenario) ==
        file +
            ":2:30: error: channels[0].output: output 'drive.power' is in W; channel 'force' "
            "measures N");
  CHECK(bench_error("channels:\n  - {channel: force, output: load.force, unit: mm}\n", scenario) ==
        file + ":2:48: error: channels[0].unit: 'mm' is not a unit of N");
  CHECK(bench_error("channels:\n  - {channel: force, output: load.force, unit: N, noise: 1 mm}\n",
                    scenario) ==
        file +
            ":2:58: error: channels[0].noise: wrong unit in '1 mm': unit 'mm' cannot be "
            "converted to 'N'; expected a force, e.g. N or mN");
}
