// discover --max-effects: the effects the runs named, refitted together with the base laws
// (identification/joint_refit.h).
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "identification/fit_report.h"
#include "identification/joint_refit.h"
#include "identification/output_error_fit.h"
#include "sim/config/config_error.h"
#include "sim/scenario.h"
#include "sim/value_check.h"
#include "tests/support/discover_data.h"
#include "tests/support/test_support.h"

using namespace tcpmsim;

namespace {

const std::string kHidden =
    "muscle.effects=[{type: hysteresis, stiffness: 50 N/m, radius: 0.12 mm}, "
    "{type: maxwell_branch, name: slow, stiffness: 1.5 N/m, time_constant: 40 s}]";

// Where the runs left the two effects: each fitted while the other was absent or held, so off
// the data's values.
const std::string kSequential =
    "muscle.effects=[{type: hysteresis, stiffness: 65 N/m, radius: 0.09 mm}, "
    "{type: maxwell_branch, name: slow, stiffness: 0.8 N/m, time_constant: 80 s}]";

fit::EffectRun named_run(int number, const std::string& out, const std::string& effect,
                         std::vector<fit::FitParameter> parameters) {
  fit::EffectRun run;
  run.number = number;
  run.directory = fit::effect_run_directory(out, number);
  run.verdict = effect;
  run.named = true;
  run.effect_parameters = std::move(parameters);
  return run;
}

// Two runs that named hysteresis, then slow relaxation, with the bounds their candidates free
// the effects' parameters in; the second run's augmented model, replaying `data`, carries both
// at `effects`.
std::vector<fit::EffectRun> two_named_runs(const std::string& out, const std::string& effects,
                                           const std::string& data) {
  const std::vector runs{named_run(1, out, "hysteresis",
                                   {{"muscle.effects[0].stiffness", "N/m", 0.0, 400.0},
                                    {"muscle.effects[0].radius", "m", 2e-5, 5e-3}}),
                         named_run(2, out, "slow_relaxation",
                                   {{"muscle.effects[1].stiffness", "N/m", 0.0, 7.0},
                                    {"muscle.effects[1].time_constant", "s", 30.0, 3000.0}})};
  std::filesystem::create_directories(runs[1].directory);
  const Scenario model = load_scenario(
      testing::source_path("configs/discover/ch7_base.yaml"),
      {effects, "measurement.file=" + data, "scenario.duration=120 s"}, testing::shared_units());
  std::ofstream(runs[1].directory + "/augmented.yaml") << model.resolved_yaml;
  return runs;
}

fit::DiscoverRequest two_effect_request() {
  const std::string data = testing::discover_measurement("joint_two_effects", {kHidden}, "120 s");
  auto request = testing::discover_request(data, {"hysteresis", "slow_relaxation"});
  request.validate_from = 80.0;
  return request;
}

double estimate(const fit::JointRefit& joint, const std::string& path) {
  for (const auto& parameter : joint.result.estimates)
    if (parameter.path == path) return parameter.value;
  FAIL("no estimate of " << path);
  return NAN;
}

}  // namespace

TEST_CASE("A joint refit is due once two runs have named an effect") {
  const auto request = two_effect_request();
  const std::string out = testing::process_directory("joint_due");
  auto runs = two_named_runs(out, kSequential, request.data_file);
  CHECK(fit::joint_refit_due(runs));
  runs[1].named = false;
  runs[1].verdict = "none";
  CHECK_FALSE(fit::joint_refit_due(runs));
}

TEST_CASE("Effects named one a run, refitted together, move to the values the data hold") {
  const auto request = two_effect_request();
  const std::string out = testing::process_directory("joint_refit");
  const auto runs = two_named_runs(out, kSequential, request.data_file);
  const fit::JointRefit joint = fit::refit_jointly(request, runs, out, testing::shared_units());
  INFO(joint.failure);
  REQUIRE(joint.failure.empty());
  INFO(fit::joint_refit_summary(joint));
  CHECK(joint.start_model == out + "/effect2/augmented.yaml");
  CHECK(joint.directory == out + "/joint");
  // The base laws' six parameters, and both effects' two.
  CHECK(joint.effect_parameters == 4);
  CHECK(joint.result.estimates.size() == 10);
  // It starts at the runs' model: its identification error can only fall.
  CHECK(joint.result.cost <= joint.result.start_cost);
  CHECK(joint.result.identification.rmse[0] <= joint.start_identification_rmse[0]);
  // Each effect's parameters end nearer the data's than the runs left them.
  const auto closer = [&](const std::string& path, double truth, double start) {
    INFO(path << ": truth " << truth << ", start " << start << ", refitted "
              << estimate(joint, path));
    CHECK(std::abs(estimate(joint, path) - truth) < std::abs(start - truth));
  };
  closer("muscle.effects[0].stiffness", 50.0, 65.0);
  closer("muscle.effects[0].radius", 1.2e-4, 0.9e-4);
  closer("muscle.effects[1].stiffness", 1.5, 0.8);
  closer("muscle.effects[1].time_constant", 40.0, 80.0);
  // On the window no fit has seen it is the better model, at the data's noise floor.
  CHECK(joint.better);
  CHECK(joint.result.validation.rmse[0] < joint.start_validation_rmse[0]);
  CHECK(joint.at_floor);
  // The runs' summary and effects.json then name it as the model that carries both effects.
  const std::string summary = fit::effect_runs_summary(runs, 3, &joint);
  CHECK_THAT(summary, Catch::Contains("refitted together (the base laws' 6 parameters and the "
                                      "named effects' 4, from " +
                                      out + "/effect2/augmented.yaml)"));
  CHECK_THAT(summary, Catch::Contains("the model with hysteresis and slow_relaxation: " + out +
                                      "/joint/fitted.yaml; it fits every output to within 25 % "
                                      "of its noise floor"));
  const auto json = nlohmann::json::parse(fit::effect_runs_json(runs, 3, &joint));
  CHECK(json["model"] == out + "/joint/fitted.yaml");
  CHECK(json["joint"]["effect_parameters"] == 4);
  CHECK(json["joint"]["better"] == true);
  CHECK(json["joint"]["validation_rmse"]["force"][1].get<double>() ==
        joint.result.validation.rmse[0]);
  // The file it names carries the refit: run as it is, it scores what the refit did.
  fit::write_fit_outputs(joint.directory, joint.spec, joint.result);
  std::string header;
  std::getline(std::ifstream(joint.directory + "/fitted.yaml"), header);
  CHECK_THAT(header, Catch::EndsWith(" by tcpmsim discover"));
  const auto written = fit::setup_discovery(
      fit::next_effect_request(request, joint.directory + "/fitted.yaml"), testing::shared_units());
  const auto& problem = written.base.problem;
  std::vector<double> own;
  const Context context = problem.model->make_context();
  for (const auto& parameter : problem.parameters) own.push_back(context.parameter(parameter.path));
  CHECK_THAT(fit::score_window(problem, own, problem.validation).rmse[0],
             Catch::WithinRel(joint.result.validation.rmse[0], 1e-9));
}

TEST_CASE("An effect its run left on a bound starts the joint refit there") {
  // An estimate on its upper bound can come back from the unit interval a rounding step beyond
  // it; the refit starts inside the box it searches. Here the branch's time constant was fitted
  // within [30 s, 80 s] and left on 80 s (the data's: 40 s).
  const std::string beyond = number_text(std::nextafter(80.0, 81.0), 17);
  const auto request = two_effect_request();
  const std::string out = testing::process_directory("joint_refit_on_bound");
  auto runs = two_named_runs(out,
                             "muscle.effects=[{type: hysteresis, stiffness: 65 N/m, radius: 0.09 "
                             "mm}, {type: maxwell_branch, name: slow, stiffness: 0.8 N/m, "
                             "time_constant: " +
                                 beyond + " s}]",
                             request.data_file);
  runs[1].effect_parameters[1].upper = 80.0;
  const fit::JointRefit joint = fit::refit_jointly(request, runs, out, testing::shared_units());
  INFO(joint.failure);
  REQUIRE(joint.failure.empty());
  const auto& time_constant = joint.result.estimates.back();
  CHECK(time_constant.path == "muscle.effects[1].time_constant");
  CHECK(time_constant.initial == 80.0);
  CHECK(time_constant.value < 50.0);
}

TEST_CASE("A joint refit that cannot be made leaves the runs' model standing") {
  const auto request = two_effect_request();
  const std::string out = testing::process_directory("joint_refit_failed");
  auto runs = two_named_runs(out, kSequential, request.data_file);
  std::filesystem::remove(runs[1].directory + "/augmented.yaml");
  const fit::JointRefit joint = fit::refit_jointly(request, runs, out, testing::shared_units());
  CHECK_THAT(joint.failure, Catch::Contains("augmented.yaml"));
  CHECK_THAT(fit::effect_runs_summary(runs, 3, &joint),
             Catch::Contains("refitted together: failed (") &&
                 Catch::Contains("the model with hysteresis and slow_relaxation: " + out +
                                 "/effect2/augmented.yaml"));
  const auto json = nlohmann::json::parse(fit::effect_runs_json(runs, 3, &joint));
  CHECK(json["joint"]["model"].is_null());
  CHECK(json["model"] == out + "/effect2/augmented.yaml");
}

TEST_CASE("A discover into a directory removes the joint refit an earlier one left there") {
  const std::filesystem::path out = testing::process_directory("earlier_joint_refit");
  std::filesystem::create_directories(out / "joint");
  std::ofstream(out / "effects.json") << "{}\n";
  std::ofstream(out / "joint" / "fit.json") << "{}\n";
  CHECK(fit::remove_earlier_effect_runs(out.string()).size() == 2);
  CHECK(!std::filesystem::exists(out / "joint"));
  // A model there is refused: the joint refit writes over it.
  fit::DiscoverRequest request;
  request.model_file = (out / "joint" / "fitted.yaml").string();
  request.data_file = "measured.csv";
  CHECK_NOTHROW(fit::check_outside_effect_runs(request, out.string(), 1));
  CHECK_THROWS_AS(fit::check_outside_effect_runs(request, out.string(), 2), UsageError);
}

TEST_CASE("A joint refit that validates worse than the runs' model leaves that model standing") {
  const std::vector runs{named_run(1, "out", "hysteresis", {}),
                         named_run(2, "out", "slow_relaxation", {})};
  fit::JointRefit joint;
  joint.directory = "out/joint";
  joint.start_model = "out/effect2/augmented.yaml";
  joint.effect_parameters = 4;
  joint.spec.problem.outputs = {{"force", "drive.force", "N", 1e-3}};
  joint.result.estimates.resize(10);
  joint.start_identification_rmse = {1.10e-3};
  joint.result.identification.rmse = {1.05e-3};
  joint.start_validation_rmse = {1.20e-3};
  joint.result.validation.rmse = {1.30e-3};
  joint.better = false;
  const std::string summary = fit::effect_runs_summary(runs, 2, &joint);
  CHECK_THAT(summary, Catch::Contains("identification error force 1.1 -> 1.05 mN"));
  CHECK_THAT(summary, Catch::Contains("validation error force 1.2 -> 1.3 mN"));
  CHECK_THAT(summary, Catch::Contains("worse on the validation window than the runs' model, "
                                      "which stands"));
  CHECK_THAT(summary, Catch::Contains("the model with hysteresis and slow_relaxation: "
                                      "out/effect2/augmented.yaml"));
  const auto json = nlohmann::json::parse(fit::effect_runs_json(runs, 2, &joint));
  CHECK(json["model"] == "out/effect2/augmented.yaml");
  CHECK(json["joint"]["model"] == "out/joint/fitted.yaml");
  CHECK(json["joint"]["better"] == false);
  CHECK(json["joint"]["validation_rmse"]["force"] == nlohmann::json({1.20e-3, 1.30e-3}));
}
