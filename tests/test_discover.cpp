// tcpmsim discover (issue 12): data made by a model that holds an effect the base model lacks
// must give that effect's name and a smaller validation error; data without one must give
// none. The pieces are checked against their definitions.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "identification/bench_measurement.h"
#include "identification/discovery.h"
#include "identification/discovery_report.h"
#include "sim/random_stream.h"
#include "sim/run.h"
#include "tests/support/test_support.h"

using namespace tcpmsim;
using namespace tcpmsim::testing;

namespace {

const std::string kBase = "configs/discover/ch7_base.yaml";

// A measurement of the base model with `hidden` overrides (the effect it holds), read by the
// chapter-7 bench: load cell 0.5 mN resolution and 1 mN noise, L* jitter and spikes.
std::string measurement(const std::string& name, std::vector<std::string> hidden) {
  // The protocol cut to 200 s of multisines to identify and 100 s of random steps to validate,
  // to keep the suite quick; the whole protocol is scripts/discover_matrix.py's.
  hidden.push_back("measurement.file=" + protocol_record("300 s"));
  hidden.push_back("scenario.duration=300 s");
  const Scenario truth = load_scenario(source_path(kBase), hidden, shared_units());
  const auto bench =
      fit::load_bench(source_path("configs/discover/ch7_bench.yaml"), truth, shared_units());
  const std::string path =
      (std::filesystem::path(process_directory("discover")) / (name + ".csv")).string();
  std::ofstream(path) << fit::measure(truth, bench, *shared_units());
  return path;
}

fit::DiscoverRequest request(const std::string& data, std::vector<std::string> effects) {
  fit::DiscoverRequest request;
  request.model_file = source_path(kBase);
  request.data_file = data;
  request.inputs = {"power", "deflection"};
  request.outputs = {"force"};
  request.validate_from = 200.0;
  request.effects = std::move(effects);
  return request;
}

std::string setup_error(const fit::DiscoverRequest& request) {
  try {
    fit::setup_discovery(request, shared_units());
  } catch (const UsageError& error) {
    return error.what();
  }
  return "";
}

}  // namespace

TEST_CASE("BIC is sum_k n ln(RSS_k / n) + p ln N for a fit with one unknown variance per output") {
  fit::WindowScore score;
  score.samples = 400;
  score.rmse = {2e-3, 5e-4};
  const double expected = 400 * std::log(4e-6) + 400 * std::log(2.5e-7) + 7 * std::log(800.0);
  CHECK(fit::bic(score, 7) == Approx(expected).epsilon(1e-14));
  // One more parameter must buy a relative drop in RSS of more than ln(N) / n to pay for itself.
  fit::WindowScore better = score;
  better.rmse[0] *= std::sqrt(std::exp(-std::log(800.0) / 400)) * 0.999;
  CHECK(fit::bic(better, 8) < fit::bic(score, 7));
  CHECK(fit::combined_rmse({2e-3, 5e-4}, {1e-3, 1e-3}) ==
        Approx(std::sqrt((4.0 + 0.25) / 2)).epsilon(1e-14));
}

TEST_CASE("Spikes are replaced; a noisy smooth signal and a noisy staircase are left alone") {
  const std::size_t n = 10000;
  RandomStream stream(3, "hampel");
  std::vector<double> time(n), values(n), truth(n);
  for (std::size_t i = 0; i < n; ++i) {
    time[i] = static_cast<double>(i) / 16.0;
    truth[i] = 0.1 * std::sin(2 * std::numbers::pi * 0.05 * time[i]);
    values[i] = truth[i] + 1e-3 * stream.normal();
  }
  const MeasuredData clean("clean", time, {{"force", "N", "N", values}});
  std::vector<std::size_t> replaced;
  const MeasuredData same = fit::without_spikes(clean, {"force"}, {}, replaced);
  CHECK(replaced == std::vector<std::size_t>{0});
  CHECK(same.find("force")->values == values);
  const std::vector<std::size_t> spikes = {10, 2000, 2001, 5000, 9990};
  for (std::size_t i : spikes) values[i] += (i % 2 ? -1 : 1) * 0.02;  // 20 standard deviations
  const MeasuredData spiked("spiked", time, {{"force", "N", "N", values}});
  const MeasuredData cleaned = fit::without_spikes(spiked, {"force"}, {}, replaced);
  CHECK(replaced == std::vector<std::size_t>{spikes.size()});
  for (std::size_t i : spikes) CHECK(std::abs(cleaned.find("force")->values[i] - truth[i]) < 5e-3);
  // Steps of 40 standard deviations every 37 samples (a force under random deflection steps).
  std::vector<double> stairs(n);
  for (std::size_t i = 0; i < n; ++i)
    stairs[i] = 0.04 * static_cast<double>((i / 37) % 5) + 1e-3 * stream.normal();
  const MeasuredData steps("steps", time, {{"force", "N", "N", stairs}});
  CHECK(fit::without_spikes(steps, {"force"}, {}, replaced).find("force")->values == stairs);
  CHECK(replaced == std::vector<std::size_t>{0});
  // A one-sample pulse of an input drives a true one in the output, which stays.
  std::vector<double> deflection(n, 0.02), pulse = stairs;
  deflection[500] = 0.03;
  pulse[500] += 0.05;
  const MeasuredData driven("driven", time,
                            {{"force", "N", "N", pulse}, {"deflection", "m", "m", deflection}});
  CHECK(fit::without_spikes(driven, {"force"}, {"deflection"}, replaced).find("force")->values ==
        pulse);
  CHECK(replaced == std::vector<std::size_t>{0});
  CHECK(std::abs(fit::without_spikes(driven, {"force"}, {}, replaced).find("force")->values[500] -
                 stairs[500]) < 0.01);
}

TEST_CASE("discover refuses a request it cannot serve, before any fit, and says why") {
  const std::string data = measurement("null", {});
  auto bad = request(data, {});
  bad.inputs = {"power", "current"};
  CHECK_THAT(setup_error(bad), Catch::Contains("--inputs") && Catch::Contains("'current'"));
  bad = request(data, {});
  bad.inputs = {"power", "force"};
  CHECK_THAT(setup_error(bad),
             Catch::Contains("replays no channel 'force'") && Catch::Contains("power, deflection"));
  bad = request(data, {});
  bad.outputs = {"force=load.forse"};
  CHECK_THAT(setup_error(bad), Catch::Contains("the model has no output 'load.forse'"));
  bad = request(data, {});
  bad.outputs = {"force=drive.power"};
  CHECK_THAT(setup_error(bad), Catch::Contains("is in N and output 'drive.power' in W"));
  bad = request(data, {"hysteresis", "warm_up"});
  CHECK_THAT(setup_error(bad), Catch::Contains("no effect 'warm_up'"));
  bad = request(data, {});
  bad.validate_from = 299.5;
  CHECK_THAT(setup_error(bad), Catch::Contains("both windows need 16 samples"));
  bad = request(data, {});
  bad.parameters = {"muscle.mechanics.k3"};
  CHECK_THAT(setup_error(bad), Catch::Contains("no parameter 'muscle.mechanics.k3'"));
  // The default parameters are the force model's six (7.1), (7.5)-(7.6); the windows split at
  // the validation time.
  const auto setup = fit::setup_discovery(request(data, {}), shared_units());
  CHECK(setup.base.problem.parameters.size() == 6);
  CHECK(setup.base.problem.outputs[0].output == "load.force");
  CHECK(setup.base.problem.identification.to < 200.0);
  CHECK(setup.base.problem.validation.from == 200.0);
}

TEST_CASE("Hysteresis hidden in the data is named, and attaching it shrinks the validation gap") {
  const std::string data = measurement(
      "hysteresis", {"muscle.effects=[{type: hysteresis, stiffness: 50 N/m, force: 6 mN}]"});
  const auto setup = fit::setup_discovery(
      request(data, {"hysteresis", "slow_relaxation", "nonlinear_stiffness"}), shared_units());
  const fit::Discovery found = fit::discover(setup);
  INFO(fit::discovery_summary(found));
  CHECK(found.verdict == "hysteresis");
  const auto& best = found.candidates.front();
  CHECK(best.delta_bic < -100);
  CHECK(best.gap_shrink > 0.3);
  // With the effect the model explains the data down to the load cell's noise (1 mN, 0.5 mN
  // resolution: sqrt(1 + 0.5^2/12) = 1.01 mN).
  CHECK(best.validation_rmse[0] < 1.2e-3);
  // The base model's residual shows the signature: it follows the direction of the last motion.
  CHECK(found.diagnostics.feature(0, "last direction of motion") > 3 * found.diagnostics.bound);
}

TEST_CASE("Data without a hidden effect give the verdict none") {
  const std::string data = measurement("null", {});
  const auto setup = fit::setup_discovery(
      request(data, {"hysteresis", "slow_relaxation", "nonlinear_stiffness"}), shared_units());
  const fit::Discovery found = fit::discover(setup);
  INFO(fit::discovery_summary(found));
  CHECK(found.verdict == "none");
  // The base model fits to the noise, and its residual is white.
  CHECK(found.base.validation.rmse[0] < 1.2e-3);
  CHECK(found.diagnostics.outputs[0].whiteness.p_value > 1e-3);
  for (const auto& candidate : found.candidates) CHECK_FALSE(candidate.significant);
}
