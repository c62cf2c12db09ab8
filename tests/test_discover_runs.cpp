// discover --max-effects: one effect a run, each run from the model the one before wrote, until
// the model fits to the noise floor (identification/discovery_runs.h).
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "identification/discovery_runs.h"
#include "sim/config/config_error.h"
#include "tests/support/test_support.h"

using namespace tcpmsim;

namespace {

fit::EffectRun named(int number, const std::string& effect, double gap_closed,
                     const std::string& still_missed) {
  fit::EffectRun run;
  run.number = number;
  run.directory = fit::effect_run_directory("out", number);
  run.verdict = effect;
  run.named = true;
  run.gap_closed = gap_closed;
  run.still_missed = still_missed;
  return run;
}

fit::EffectRun unnamed(int number, const std::string& verdict) {
  fit::EffectRun run;
  run.number = number;
  run.directory = fit::effect_run_directory("out", number);
  run.verdict = verdict;
  if (verdict == "failed") run.failure = "the base model's fit failed: no finite cost";
  return run;
}

nlohmann::json json_of(const std::vector<fit::EffectRun>& runs, int max_effects) {
  return nlohmann::json::parse(fit::effect_runs_json(runs, max_effects));
}

}  // namespace

TEST_CASE("The first run writes into --out, each later one into its own directory there") {
  CHECK(fit::effect_run_directory("results/d", 1) == "results/d");
  CHECK(fit::effect_run_directory("results/d", 2) == "results/d/effect2");
  CHECK(fit::effect_run_directory("results/d", 10) == "results/d/effect10");
}

TEST_CASE("The next run starts from the model the run before wrote, with its overrides in it") {
  fit::DiscoverRequest first;
  first.model_file = "model.yaml";
  first.data_file = "measured.csv";
  first.outputs = {"force"};
  first.effects = {"hysteresis", "slow_relaxation"};
  first.overrides = {"muscle.k1=420 N/m"};
  first.validate_from = 400.0;
  const auto next = fit::next_effect_request(first, "out/augmented.yaml");
  CHECK(next.model_file == "out/augmented.yaml");
  CHECK(next.overrides.empty());
  CHECK(next.data_file == first.data_file);
  CHECK(next.outputs == first.outputs);
  CHECK(next.effects == first.effects);
  CHECK(next.validate_from == first.validate_from);
}

TEST_CASE("The runs' summary names the model that carries every named effect and how it fits") {
  SECTION("Two effects, and with both the model fits to the floor") {
    const std::vector runs{named(1, "hysteresis", 0.355, "force 3.66 times"),
                           named(2, "slow_relaxation", 0.993, "")};
    const std::string summary = fit::effect_runs_summary(runs, 3);
    CHECK_THAT(summary, Catch::Contains("1  hysteresis: closes 35.5 % of the gap above the noise "
                                        "floor (out)"));
    CHECK_THAT(summary, Catch::Contains("2  slow_relaxation: closes 99.3 % of the gap above the "
                                        "noise floor that remained (out/effect2)"));
    CHECK_THAT(summary, Catch::Contains("the model with hysteresis and slow_relaxation: "
                                        "out/effect2/augmented.yaml; it fits every output to "
                                        "within 25 % of its noise floor"));
    const auto json = json_of(runs, 3);
    CHECK(json["effects"] == nlohmann::json({"hysteresis", "slow_relaxation"}));
    CHECK(json["model"] == "out/effect2/augmented.yaml");
    CHECK(json["at_noise_floor"] == true);
    CHECK(json["runs"].size() == 2);
    CHECK(json["runs"][0]["still_missed"] == "force 3.66 times");
  }
  SECTION("The last run allowed still misses: raise --max-effects") {
    const std::vector runs{named(1, "hysteresis", 0.355, "force 3.66 times"),
                           named(2, "slow_relaxation", 0.5, "force 1.8 times")};
    CHECK_THAT(fit::effect_runs_summary(runs, 2),
               Catch::Contains("it still misses the noise floor (force 1.8 times): --max-effects "
                               "reached, raise it to look for another"));
    CHECK(json_of(runs, 2)["at_noise_floor"] == false);
  }
  SECTION("Refitted with the first effect, the model fits to the floor: its refit is the model") {
    const std::vector runs{named(1, "hysteresis", 0.8, "force 1.4 times"), unnamed(2, "none")};
    CHECK_THAT(fit::effect_runs_summary(runs, 3),
               Catch::Contains("the model with hysteresis: out/effect2/baseline.yaml; it fits "
                               "every output to within 25 % of its noise floor"));
    CHECK(json_of(runs, 3)["at_noise_floor"] == true);
  }
  SECTION("No candidate explains what the first effect leaves") {
    const std::vector runs{named(1, "hysteresis", 0.8, "force 1.4 times"),
                           unnamed(2, "unexplained")};
    const std::string summary = fit::effect_runs_summary(runs, 3);
    CHECK_THAT(summary, Catch::Contains("2  unexplained: the model misses by more than the noise "
                                        "and no candidate explains it (out/effect2)"));
    CHECK_THAT(summary, Catch::Contains("out/effect2/baseline.yaml; it still misses the noise "
                                        "floor, and no candidate explains the rest"));
    CHECK(json_of(runs, 3)["at_noise_floor"] == false);
  }
  SECTION("A later run that fails leaves the model of the run before") {
    const std::vector runs{named(1, "hysteresis", 0.8, "force 1.4 times"), unnamed(2, "failed")};
    const std::string summary = fit::effect_runs_summary(runs, 3);
    CHECK_THAT(summary, Catch::Contains("2  failed: the base model's fit failed"));
    CHECK_THAT(summary, Catch::Contains("the model with hysteresis: out/augmented.yaml; it still "
                                        "misses the noise floor (force 1.4 times)\n"));
    const auto json = json_of(runs, 3);
    CHECK(json["model"] == "out/augmented.yaml");
    CHECK(json["runs"][1]["gap_closed"].is_null());
  }
  SECTION("A family named twice is counted once") {
    const std::vector runs{named(1, "hysteresis", 0.8, "force 1.7 times"),
                           named(2, "hysteresis", 0.4, "force 1.4 times"),
                           named(3, "slow_relaxation", 0.9, "")};
    CHECK_THAT(fit::effect_runs_summary(runs, 3),
               Catch::Contains("the model with hysteresis x2 and slow_relaxation: "
                               "out/effect3/augmented.yaml"));
    CHECK(json_of(runs, 3)["effects"] ==
          nlohmann::json({"hysteresis", "hysteresis", "slow_relaxation"}));
  }
  SECTION("A first run that names nothing leaves no model") {
    const std::vector runs{unnamed(1, "none")};
    CHECK_THAT(fit::effect_runs_summary(runs, 3), Catch::Contains("no effect named"));
    const auto json = json_of(runs, 3);
    CHECK(json["model"].is_null());
    CHECK(json["at_noise_floor"].is_null());
    CHECK(json["effects"].empty());
  }
}

TEST_CASE("A discover into a directory removes the later runs an earlier discover left there") {
  const std::filesystem::path out = tcpmsim::testing::process_directory("earlier_effect_runs");
  std::filesystem::create_directories(out / "effect2");
  std::filesystem::create_directories(out / "effect3");
  std::filesystem::create_directories(out / "effect5");  // not the run after the last
  for (const auto* file : {"effects.json", "discovery.json", "notes.txt", "effect2/discovery.json",
                           "effect5/discovery.json"})
    std::ofstream(out / file) << "{}\n";
  // effect3 is empty: a run whose base fit failed.
  const auto removed = fit::remove_earlier_effect_runs(out.string());
  CHECK(removed.size() == 3);
  CHECK(!std::filesystem::exists(out / "effects.json"));
  CHECK(!std::filesystem::exists(out / "effect2"));
  CHECK(!std::filesystem::exists(out / "effect3"));
  CHECK(std::filesystem::exists(out / "effect5"));
  CHECK(std::filesystem::exists(out / "discovery.json"));  // the first run's, written over
  CHECK(std::filesystem::exists(out / "notes.txt"));
  CHECK(fit::remove_earlier_effect_runs(out.string()).empty());
}

TEST_CASE("Directories named like later runs are someone else's without an earlier effects.json") {
  const std::filesystem::path out = tcpmsim::testing::process_directory("no_earlier_runs");
  std::filesystem::create_directories(out / "effect2");
  std::ofstream(out / "effect2" / "discovery.json") << "{}\n";
  std::ofstream(out / "effect3") << "a file, not a run\n";
  CHECK(fit::earlier_effect_runs(out.string()).empty());
  CHECK(fit::remove_earlier_effect_runs(out.string()).empty());
  CHECK(std::filesystem::exists(out / "effect2" / "discovery.json"));
  // With the marker, a file named like a run is not one: the runs end before it.
  std::filesystem::remove_all(out / "effect2");
  std::ofstream(out / "effects.json") << "{}\n";
  CHECK(fit::remove_earlier_effect_runs(out.string()) ==
        std::vector<std::string>{(out / "effects.json").string()});
  CHECK(std::filesystem::exists(out / "effect3"));
}

TEST_CASE("A model or measurement where discover writes is refused before any run") {
  const std::filesystem::path out = tcpmsim::testing::process_directory("inputs_in_out");
  fit::DiscoverRequest request;
  request.model_file = (out / "augmented.yaml").string();
  request.data_file = "measured.csv";
  // The first run writes its augmented model over it.
  CHECK_THROWS_WITH(fit::check_outside_effect_runs(request, out.string(), 1),
                    Catch::Contains("--model " + request.model_file +
                                    " is a file this discover writes over (--out " + out.string() +
                                    "); copy it elsewhere or give another --out"));
  // A later run writes its directory over it.
  request.model_file = (out / "effect2" / "augmented.yaml").string();
  CHECK_NOTHROW(fit::check_outside_effect_runs(request, out.string(), 1));
  CHECK_THROWS_AS(fit::check_outside_effect_runs(request, out.string(), 2), UsageError);
  CHECK_THROWS_WITH(fit::check_outside_effect_runs(request, out.string(), 2),
                    Catch::Contains("lies in " + (out / "effect2").string() +
                                    ", a directory this "
                                    "discover writes over"));
  request.model_file = "model.yaml";
  request.data_file = (out / "effect3" / "measured.csv").string();
  CHECK_THROWS_WITH(fit::check_outside_effect_runs(request, out.string(), 3),
                    Catch::StartsWith("--data "));
  // Beside the output directory, or in a directory merely named like it, is fine.
  request.data_file = out.string() + "_data/measured.csv";
  CHECK_NOTHROW(fit::check_outside_effect_runs(request, out.string(), 3));
}
