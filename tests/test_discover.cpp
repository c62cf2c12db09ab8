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
#include "identification/noise_floor.h"
#include "identification/residual_diagnostics.h"
#include "sim/random_stream.h"
#include "sim/run.h"
#include "tests/support/discover_data.h"
#include "tests/support/test_support.h"

using namespace tcpmsim;
using namespace tcpmsim::testing;

namespace {

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

TEST_CASE(
    "A residual's samples count for (1 - rho) / (1 + rho) of white ones, rho its lag-1 "
    "autocorrelation") {
  // First-order noise e_i = phi e_(i-1) + w_i: rho = phi, to its sampling error.
  RandomStream stream(11, "evidence share");
  const std::size_t n = 20000;
  for (const double phi : {0.0, 0.5, 0.9}) {
    std::vector<double> series(n);
    for (std::size_t i = 1; i < n; ++i) series[i] = phi * series[i - 1] + stream.normal();
    const double rho = fit::autocorrelation(series, 1)[1];
    INFO("phi " << phi);
    CHECK(rho == Approx(phi).margin(4.0 / std::sqrt(double(n))));
    const double counted = std::max(rho, 0.0);  // white noise's rho may fall below 0
    CHECK(fit::evidence_share(series) == Approx((1 - counted) / (1 + counted)).epsilon(1e-12));
  }
  // A residual that alternates is not rewarded: rho is clamped at 0.
  std::vector<double> alternating(n);
  for (std::size_t i = 0; i < n; ++i) alternating[i] = (i % 2 ? 1.0 : -1.0) + 0.1 * stream.normal();
  CHECK(fit::evidence_share(alternating) == 1.0);
  // The BIC change weighs each output's log-likelihood term by its share; the parameters' price
  // p ln N stays whole.
  fit::WindowScore base, candidate;
  base.samples = candidate.samples = 400;
  base.rmse = {2e-3, 5e-4};
  candidate.rmse = {1.5e-3, 5e-4};
  CHECK(fit::bic_change(candidate, 9, base, 7, {1.0, 1.0}) ==
        Approx(fit::bic(candidate, 9) - fit::bic(base, 7)).epsilon(1e-12));
  CHECK(fit::bic_change(candidate, 9, base, 7, {0.25, 1.0}) ==
        Approx(0.25 * 400 * std::log(0.5625) + 2 * std::log(800.0)).epsilon(1e-12));
}

TEST_CASE("The base model is at the noise floor by the size of its residual, not its whiteness") {
  // Data from another implementation of the same laws at 1 mN of noise (the independent
  // matrix's null case): RMSE 1.0405 mN over a floor of 1.0143 mN, Ljung-Box p = 2e-5. The
  // residual is structured, but its structured part is a fifth of the noise: at the floor.
  CHECK(fit::at_noise_floor({1.0405e-3, 5.44e-4}, {1.0143e-3, 4.93e-4}, 0.25) ==
        std::vector<bool>{true, true});
  CHECK(fit::structured_rms(1.0405e-3, 1.0143e-3) ==
        Approx(std::sqrt(1.0405e-3 * 1.0405e-3 - 1.0143e-3 * 1.0143e-3)).epsilon(1e-12));
  CHECK(fit::structured_rms(1.0405e-3, 1.0143e-3) == Approx(0.232e-3).epsilon(0.01));
  // Issue 28's hysteresis case: 8.9 mN over a 2 mN floor is far above it, on one output
  // enough to stop the verdict none.
  CHECK(fit::at_noise_floor({8.91e-3, 5e-4}, {2e-3, 5e-4}, 0.25) == std::vector<bool>{false, true});
  // The margin is the bound; a residual below the floor has no structured part.
  CHECK(fit::at_noise_floor({1.2499e-3}, {1e-3}, 0.25) == std::vector<bool>{true});
  CHECK(fit::at_noise_floor({1.2501e-3}, {1e-3}, 0.25) == std::vector<bool>{false});
  CHECK(fit::structured_rms(0.9e-3, 1e-3) == 0.0);
}

TEST_CASE(
    "A named effect closes its share of the gap of the outputs the base model misses, however "
    "close the others are to their floors") {
  // A held-out thermal lag (a holder mass beside the polymer, 2 mN): the base misses the force
  // by 1.38 floors while L* is at 1.10, so the outputs combined (1.245) are within the 25 %
  // margin, yet `none` is ruled out by the force. A one-branch relaxation that moved the force
  // from 2.7825 to 2.7775 mN closes under 1 % of the force's gap: not what is missing.
  const std::vector<double> floor = {2.0213e-3, 4.9325e-4};
  const std::vector<double> base = {2.7825e-3, 5.4420e-4};
  const std::vector<double> sliver = {2.7775e-3, 5.4420e-4};
  CHECK(fit::combined_rmse(base, floor) < 1.25);
  const double force_share = (2.7825 / 2.0213 - 2.7775 / 2.0213) / (2.7825 / 2.0213 - 1.0);
  CHECK(fit::missed_gap_closed(base, sliver, floor, 0.25) == Approx(force_share).epsilon(1e-9));
  CHECK(force_share < 0.01);
  // So it is not significant, while combined with L* (the rule before) it was let through.
  CHECK_FALSE(fit::closes_enough_of_gap(base, sliver, floor, 0.25, 0.2));
  // Closing the force's gap whole is a share of one, whatever L* does within its floor.
  CHECK(fit::missed_gap_closed(base, {2.0213e-3, 5.0e-4}, floor, 0.25) ==
        Approx(1.0).epsilon(1e-9));
  // Where both outputs are missed, their gap is the combined one.
  const std::vector<double> both = {4e-3, 1e-3};
  const std::vector<double> halfway = {3e-3, 0.75e-3};
  CHECK(fit::missed_gap_closed(both, halfway, floor, 0.25) ==
        Approx(fit::above_noise_gap_closed(both, halfway, floor)).epsilon(1e-12));
  CHECK(fit::closes_enough_of_gap(base, {2.0213e-3, 5.0e-4}, floor, 0.25, 0.2));
}

TEST_CASE(
    "At the noise floor a named effect closes its share of what the base model leaves above "
    "it") {
  // The independent generator's data without an effect at 1 mN (seed 4, build ac3b316): the base
  // model within 2 % of the floors (its law is not the generator's: power held on another grid),
  // and a heat sink that took 0.1 % off the validation error was significant (delta BIC -19.7,
  // z 4.4) while closing 6.3 % of the gap above the floors: a false alarm.
  const std::vector<double> floor = {1.002296e-3, 4.919159e-4};
  const std::vector<double> base = {1.021153e-3, 5.000546e-4};
  const std::vector<double> heat_sink = {1.019850e-3, 5.000546e-4};
  CHECK(fit::at_noise_floor(base, floor, 0.25) == std::vector<bool>{true, true});
  CHECK(std::isnan(fit::missed_gap_closed(base, heat_sink, floor, 0.25)));
  const double share = fit::above_noise_gap_closed(base, heat_sink, floor);
  CHECK(share > 0.0);
  CHECK(share < 0.2);
  CHECK_FALSE(fit::closes_enough_of_gap(base, heat_sink, floor, 0.25, 0.2));
  // An effect that takes the model to its floors closes the whole gap.
  CHECK(fit::closes_enough_of_gap(base, floor, floor, 0.25, 0.2));
  // A base at or below its floors combined leaves no gap: nothing is asked.
  const std::vector<double> below = {0.99e-3, 4.9e-4};
  CHECK(std::isnan(fit::above_noise_gap_closed(below, {0.989e-3, 4.9e-4}, floor)));
  CHECK(fit::closes_enough_of_gap(below, {0.989e-3, 4.9e-4}, floor, 0.25, 0.2));
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
  const std::string data = discover_measurement("null", {});
  auto bad = discover_request(data, {});
  bad.inputs = {"power", "current"};
  CHECK_THAT(setup_error(bad), Catch::Contains("--inputs") && Catch::Contains("'current'"));
  bad = discover_request(data, {});
  bad.inputs = {"power", "force"};
  CHECK_THAT(setup_error(bad),
             Catch::Contains("replays no channel 'force'") && Catch::Contains("power, deflection"));
  bad = discover_request(data, {});
  bad.outputs = {"force=load.forse"};
  CHECK_THAT(setup_error(bad), Catch::Contains("the model has no output 'load.forse'"));
  bad = discover_request(data, {});
  bad.outputs = {"force=drive.power"};
  CHECK_THAT(setup_error(bad), Catch::Contains("is in N and output 'drive.power' in W"));
  bad = discover_request(data, {"hysteresis", "warm_up"});
  CHECK_THAT(setup_error(bad), Catch::Contains("no effect 'warm_up'"));
  bad = discover_request(data, {});
  bad.validate_from = 299.5;
  CHECK_THAT(setup_error(bad), Catch::Contains("both windows need 16 samples"));
  bad = discover_request(data, {});
  bad.parameters = {"muscle.mechanics.k3"};
  CHECK_THAT(setup_error(bad), Catch::Contains("no parameter 'muscle.mechanics.k3'"));
  // The default parameters are the force model's six (7.1), (7.5)-(7.6); the windows split at
  // the validation time.
  const auto setup = fit::setup_discovery(discover_request(data, {}), shared_units());
  CHECK(setup.base.problem.parameters.size() == 6);
  CHECK(setup.base.problem.outputs[0].output == "load.force");
  CHECK(setup.base.problem.identification.to < 200.0);
  CHECK(setup.base.problem.validation.from == 200.0);
}

TEST_CASE("Hysteresis hidden in the data is named, and attaching it shrinks the validation gap") {
  const std::string data = discover_measurement(
      "hysteresis", {"muscle.effects=[{type: hysteresis, stiffness: 50 N/m, force: 6 mN}]"});
  const auto setup = fit::setup_discovery(
      discover_request(data, {"hysteresis", "slow_relaxation", "nonlinear_stiffness"}),
      shared_units());
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

// Every stage of a discover on a short record (80 s to identify, 40 s to validate, one start):
// the base fit, the candidate's nested refit, the ranking, the diagnostics and the files. The
// case above judges the verdict on a longer record; this one is what the sanitizer tree runs.
TEST_CASE("A short discover goes through every stage and writes every file it names") {
  const auto request = short_hysteresis_request();
  const fit::Discovery found = fit::discover(fit::setup_discovery(request, shared_units()));
  INFO(fit::discovery_summary(found));
  REQUIRE(found.candidates.size() == 1);
  const auto& candidate = found.candidates.front();
  CHECK(candidate.status == "fitted");
  // Nested: the refit starts from the base optimum with the effect at zero size.
  CHECK(candidate.result.cost <= candidate.nested_cost * (1.0 + 1e-9));
  CHECK(candidate.validation_rmse[0] < found.base.validation.rmse[0]);
  CHECK(found.verdict == "hysteresis");
  const std::string directory = process_directory("discover_short");
  const auto written = fit::write_discovery(directory, found);
  CHECK(written.size() == 5);
  for (const auto& path : written) {
    INFO(path);
    CHECK(std::filesystem::file_size(path) > 0);
  }
  std::ifstream json(std::filesystem::path(directory) / "discovery.json");
  const std::string text((std::istreambuf_iterator<char>(json)), std::istreambuf_iterator<char>());
  CHECK_THAT(text, Catch::Contains("\"verdict\": \"hysteresis\""));

  // The model with the named effect takes the base model's test against the noise floor: where
  // it still misses, the summary, the report and discovery.json say so, and that another effect
  // may be missing.
  const double floor = found.setup.floor[0];
  const bool fits = candidate.validation_rmse[0] <= (1.0 + request.floor_margin) * floor;
  CHECK_THAT(text, Catch::Contains(std::string("\"at_noise_floor\": {\n      \"force\": ") +
                                   (fits ? "true" : "false")));
  fit::Discovery still_missing = found;
  still_missing.candidates.front().validation_rmse[0] = 3.0 * floor;
  CHECK_THAT(fit::discovery_summary(still_missing),
             Catch::Contains("still misses the noise floor (force 3 times)"));
  CHECK_THAT(fit::discovery_report(still_missing),
             Catch::Contains("validation RMSE force 3 times its floor): another effect may be "
                             "missing. Run discover again with `augmented.yaml` as `--model`"));
  CHECK_THAT(fit::discovery_json(still_missing),
             Catch::Contains("\"at_noise_floor\": {\n      \"force\": false"));
  // Under none, a candidate the BIC favours that closes a sliver of the gap above the floor is
  // said to be one, so that its delta BIC is not read as a missed effect.
  fit::Discovery sliver = found;
  sliver.kind = fit::VerdictKind::none;
  sliver.verdict = "none";
  sliver.candidates.front().significant = false;
  sliver.candidates.front().delta_bic = -19.7;
  sliver.candidates.front().gap_closed = 0.063;
  CHECK_THAT(fit::discovery_report(sliver),
             Catch::Contains("lowers the BIC by 19.7 (signature z ") &&
                 Catch::Contains(") but closes 6.3 % of the gap the base model leaves above the "
                                 "noise floor, under the 20 % a named effect must close"));
  sliver.candidates.front().gap_closed = 0.5;
  CHECK_THAT(fit::discovery_report(sliver), !Catch::Contains("a trace of the model's own misfit"));
  fit::Discovery at_floor = found;
  at_floor.candidates.front().validation_rmse[0] = floor;
  CHECK_THAT(fit::discovery_summary(at_floor), !Catch::Contains("still misses"));
  CHECK_THAT(fit::discovery_report(at_floor),
             Catch::Contains("With it the model fits every output to within"));
}

TEST_CASE("The noise floor is read from the data: white noise under a smooth signal and steps") {
  const std::size_t n = 8000;
  RandomStream stream(5, "floor");
  std::vector<double> values(n), deflection(n), grid(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) / 16.0;
    // A force under a multisine and deflection steps every 5 s (the step moves it at once).
    deflection[i] = 0.01 * static_cast<double>((i / 80) % 3);
    values[i] = 0.1 * std::sin(2 * std::numbers::pi * 0.08 * t) + 13.5 * deflection[i] +
                2e-3 * stream.normal();
    grid[i] =
        std::round((0.1 * std::sin(2 * std::numbers::pi * 0.08 * t) + 1e-4 * stream.normal()) /
                   5e-4) *
        5e-4;
  }
  // Where the input jumps, the force's differences hold its response: left out, the floor is the
  // noise's; left in, they bias it up.
  const auto steps = fit::steps_in_inputs({&deflection}, n);
  CHECK(fit::difference_noise_floor(values, steps) == Approx(2e-3).epsilon(0.03));
  CHECK(fit::difference_noise_floor(values) > fit::difference_noise_floor(values, steps));
  // Noise finer than the grid: at least the grid's rounding, q / sqrt(12).
  CHECK(fit::difference_noise_floor(grid) >= 5e-4 / std::sqrt(12.0));
  CHECK(fit::difference_noise_floor(grid) < 2e-4);
  CHECK(std::isnan(fit::difference_noise_floor({1.0, 2.0})));
}

TEST_CASE("Inputs on a grid or held between steps do not shield output spikes at smooth peaks") {
  // The chapter-7 bench: a multisine deflection read on a 0.02 mm grid, a power held between
  // steps, and L* with spikes beside the multisine's peaks; every spike goes.
  const std::size_t n = 6400;
  RandomStream stream(8, "grid");
  std::vector<double> time(n), deflection(n), power(n), measure(n);
  for (std::size_t i = 0; i < n; ++i) {
    time[i] = static_cast<double>(i) / 16.0;
    deflection[i] =
        std::round((0.02 + 0.01 * std::sin(2 * std::numbers::pi * 0.05 * time[i])) / 2e-5) * 2e-5;
    power[i] = 0.5 + static_cast<double>((i / 300) % 4);
    measure[i] = 2.81e-3 / (deflection[i] + 28.8e-3) + 0.433 + 5e-4 * stream.normal();
  }
  std::vector<std::size_t> spikes;
  for (std::size_t i = 80; i + 80 < n; i += 320) {  // at every other peak of the multisine
    spikes.push_back(i);
    measure[i] += 0.02;
  }
  const MeasuredData data("bench", time,
                          {{"inductance_measure", "1", "1", measure},
                           {"deflection", "m", "m", deflection},
                           {"power", "W", "W", power}});
  std::vector<std::size_t> replaced;
  const auto cleaned =
      fit::without_spikes(data, {"inductance_measure"}, {"power", "deflection"}, replaced);
  CHECK(replaced == std::vector<std::size_t>{spikes.size()});
  for (std::size_t i : spikes)
    CHECK(std::abs(cleaned.find("inductance_measure")->values[i] - measure[i] + 0.02) < 3e-3);
}

TEST_CASE("A discover tries, scores and reports the same candidates whatever --jobs is") {
  // Higher orders are guessed ahead while the first round's fits still run (run_two_rounds):
  // what is tried and reported must not depend on the number of jobs or on the timing. (Its
  // scheduling runs under ThreadSanitizer in test_parallel_rounds; this whole discover is too
  // long for that tree.)
  const std::string data = discover_measurement(
      "hysteresis_jobs", {"muscle.effects=[{type: hysteresis, stiffness: 50 N/m, force: 6 mN}]"},
      "60 s");
  auto request = discover_request(data, {"hysteresis", "ratchet"});
  request.validate_from = 40.0;
  request.starts = 1;
  request.max_order = 0;
  std::vector<fit::Discovery> found;
  for (const int threads : {1, 2}) {
    request.threads = threads;
    found.push_back(fit::discover(fit::setup_discovery(request, shared_units())));
  }
  INFO(fit::discovery_summary(found.front()));
  CHECK(found.front().verdict == "hysteresis");
  // The Prandtl-Ishlinskii operator was tried: the second round is not empty.
  CHECK(found.front().candidates.size() == 3);
  for (std::size_t run = 1; run < found.size(); ++run) {
    INFO((run + 1) << " jobs");
    CHECK(found[run].verdict == found.front().verdict);
    CHECK(found[run].simulations == found.front().simulations);
    REQUIRE(found[run].candidates.size() == found.front().candidates.size());
    for (std::size_t k = 0; k < found.front().candidates.size(); ++k) {
      const auto& a = found.front().candidates[k];
      const auto& b = found[run].candidates[k];
      INFO(a.name << " [" << a.member << "]");
      CHECK(b.member == a.member);
      CHECK(b.result.cost == a.result.cost);
      CHECK(b.delta_bic == a.delta_bic);
    }
  }
}
