// Which measured channels discover takes as the heating power and the deflection: those the
// base model replays as them, whatever the bench called them; the catalogue's scales and the
// diagnostics' features then do not depend on the names.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "identification/discovery_diagnostics.h"
#include "identification/effect_catalogue.h"
#include "identification/measured_roles.h"
#include "tests/support/discover_data.h"
#include "tests/support/test_support.h"

using namespace tcpmsim;
using namespace tcpmsim::testing;

namespace {

const char* const kPowerRenamed =
    "drive.power={type: data, channel: heater.power, interpolation: hold}";
const char* const kDeflectionRenamed =
    "load.deflection={type: data, channel: stage.deflection, interpolation: linear}";

Scenario base_model(const std::string& data, std::vector<std::string> overrides = {}) {
  overrides.push_back("measurement.file=" + data);
  overrides.push_back("scenario.duration=60 s");
  return load_scenario(source_path("configs/discover/ch7_base.yaml"), overrides, shared_units());
}

// A force that follows neither law exactly: the residual has something to correlate with.
double made_up_force(double time, double power, double deflection) {
  return 0.1 + 8.0 * deflection + 0.01 * power + 1e-3 * std::sin(0.7 * time);
}

// The protocol's power and deflection, and a made-up force, as a CSV: under the names the base
// model replays (power, deflection) or as a bench whose instruments have names writes them
// (heater.power, stage.deflection).
std::string protocol_csv(const MeasuredData& protocol, bool renamed) {
  const auto path = std::filesystem::path(process_directory("measured_roles")) /
                    (renamed ? "renamed.csv" : "named.csv");
  std::ofstream file(path);
  file << (renamed ? "time[s],heater.power[W],stage.deflection[m],force[N]\n"
                   : "time[s],power[W],deflection[m],force[N]\n");
  const auto& time = protocol.time();
  const auto& power = protocol.find("power")->values;
  const auto& deflection = protocol.find("deflection")->values;
  for (std::size_t i = 0; i < time.size(); ++i)
    file << number(time[i]) << "," << number(power[i]) << "," << number(deflection[i]) << ","
         << number(made_up_force(time[i], power[i], deflection[i])) << "\n";
  return path.string();
}

struct Measurement {
  std::string path;
  MeasuredData data;
  Scenario model;
};

Measurement measurement(bool renamed) {
  const MeasuredData protocol = read_measured_data(protocol_record("60 s"), *shared_units());
  const std::string path = protocol_csv(protocol, renamed);
  std::vector<std::string> overrides;
  if (renamed) overrides = {kPowerRenamed, kDeflectionRenamed};
  return {path, read_measured_data(path, *shared_units()), base_model(path, overrides)};
}

const fit::EffectCandidate* first_of(const fit::Candidates& candidates, const std::string& name) {
  for (const auto& candidate : candidates.candidates)
    if (candidate.name == name) return &candidate;
  return nullptr;
}

}  // namespace

TEST_CASE("A measured quantity is the channel replayed as it, else compared as it, else named so") {
  const Measurement renamed = measurement(true);
  const fit::MeasuredRoles roles = fit::measured_roles(renamed.model, renamed.data, {});
  CHECK(roles.power == "heater.power");
  CHECK(roles.deflection == "stage.deflection");
  // Compared: no data signal stands under "temperature"; an output compared as one does.
  const std::vector<fit::FitOutput> outputs{{"force", "muscle.temperature", "K", 1.0}};
  CHECK(fit::channel_carrying(renamed.model, renamed.data, outputs, "temperature") == "force");
  // Named: neither replayed nor compared, the channel of that name.
  CHECK(fit::channel_carrying(renamed.model, renamed.data, {}, "force") == "force");
  // None of these: the name itself, which the data do not hold.
  CHECK(fit::channel_carrying(renamed.model, renamed.data, {}, "voltage") == "voltage");
  // Named power and deflection, as chapter 7's base model replays them.
  const Measurement named = measurement(false);
  const fit::MeasuredRoles named_roles = fit::measured_roles(named.model, named.data, {});
  CHECK(named_roles.power == "power");
  CHECK(named_roles.deflection == "deflection");
}

TEST_CASE("The catalogue's families and scales do not depend on what the channels are called") {
  const Measurement renamed = measurement(true);
  const Measurement named = measurement(false);
  const fit::MeasuredRoles roles = fit::measured_roles(renamed.model, renamed.data, {});
  const auto by_role = fit::effect_candidates(renamed.model, renamed.model.make_context(),
                                              renamed.data, {"load.force"}, {roles, 0.0});
  const auto by_name =
      fit::effect_candidates(named.model, named.model.make_context(), named.data, {"load.force"});
  REQUIRE(by_role.skipped.size() == 1);
  CHECK(by_role.skipped[0].name == "inductance_temperature");
  CHECK(candidate_names(by_role) == candidate_names(by_name));
  // The knee's place, the play operators' radii (the deflection's range) and the fan's power
  // scale (the power's peak).
  for (const std::string family :
       {"nonlinear_stiffness", "hysteresis", "heating_dependent_convection"}) {
    INFO(family);
    const auto* mine = first_of(by_role, family);
    const auto* theirs = first_of(by_name, family);
    REQUIRE(mine);
    REQUIRE(theirs);
    REQUIRE(mine->parameters.size() == theirs->parameters.size());
    for (std::size_t j = 0; j < mine->parameters.size(); ++j) {
      INFO(mine->parameters[j].path);
      CHECK(mine->parameters[j].lower == theirs->parameters[j].lower);
      CHECK(mine->parameters[j].upper == theirs->parameters[j].upper);
      CHECK(mine->nested[j] == theirs->nested[j]);
    }
  }
  // Looked up by name alone, the renamed data hold neither: those families would go.
  const auto by_default = fit::effect_candidates(renamed.model, renamed.model.make_context(),
                                                 renamed.data, {"load.force"});
  std::vector<std::string> skipped;
  for (const auto& entry : by_default.skipped) skipped.push_back(entry.name);
  CHECK(skipped == std::vector<std::string>{"nonlinear_stiffness", "inductance_temperature",
                                            "heating_dependent_convection"});
}

TEST_CASE("The diagnostics hold the residual against the power and deflection, whatever names") {
  const auto problem_of = [](const Measurement& measured) {
    fit::FitProblem problem;
    problem.model = std::make_shared<const Scenario>(measured.model);
    problem.data = std::make_shared<const MeasuredData>(measured.data);
    problem.outputs = {{"force", "load.force", "N", 1e-3}};
    problem.identification = {0.0, 30.0};
    problem.validation = {30.0, 60.0};
    return problem;
  };
  const Measurement renamed = measurement(true);
  const Measurement named = measurement(false);
  const auto by_role = fit::diagnose(problem_of(renamed), {}, {"heater.power", "stage.deflection"},
                                     fit::measured_roles(renamed.model, renamed.data, {}));
  const auto by_name = fit::diagnose(problem_of(named), {}, {"power", "deflection"});
  REQUIRE(by_role.features.size() == by_name.features.size());
  for (std::size_t j = 0; j < by_name.features.size(); ++j) {
    INFO(by_name.features[j].name);
    CHECK(by_role.features[j].name == by_name.features[j].name);
    CHECK(by_role.features[j].values == by_name.features[j].values);
    CHECK(by_role.feature(0, by_name.features[j].name) ==
          by_name.feature(0, by_name.features[j].name));
  }
  for (const char* feature : {"power", "deflection", "last direction of motion"}) {
    INFO(feature);
    CHECK(std::isfinite(by_role.feature(0, feature)));
  }
  CHECK(by_role.outputs[0].loop.frequency == by_name.outputs[0].loop.frequency);
  CHECK_FALSE(by_role.outputs[0].loop.frequency.empty());
  // The thermal lag's evidence, the residual's cross-correlation with the power, is found.
  const std::string evidence = fit::signature_evidence("thermal_lag", by_role, problem_of(renamed));
  CHECK(evidence == fit::signature_evidence("thermal_lag", by_name, problem_of(named)));
  CHECK_THAT(evidence, Catch::Contains("cross-correlation with power peaks at"));
}
