// discover's catalogue of named effects: every candidate attaches to the chapter-7 base model,
// runs, and frees parameters that exist with bounds around its start; what cannot attach says
// why.
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <map>

#include "identification/effect_catalogue.h"
#include "models/effects/effect_candidates.h"
#include "models/muscle.h"
#include "sim/run.h"
#include "tests/support/discover_data.h"
#include "tests/support/test_support.h"

using namespace tcpmsim;
using namespace tcpmsim::testing;

namespace {

Scenario base_model(const std::string& data, std::vector<std::string> overrides = {}) {
  overrides.push_back("measurement.file=" + data);
  overrides.push_back("scenario.duration=60 s");
  return load_scenario(source_path("configs/discover/ch7_base.yaml"), overrides, shared_units());
}

}  // namespace

TEST_CASE("The catalogue names the ten effect families of the discovery workflow exactly") {
  CHECK(fit::effect_names() ==
        std::vector<std::string>{
            "slow_relaxation", "hysteresis", "nonlinear_convection", "thermal_lag",
            "nonlinear_stiffness", "temperature_dependent_stiffness", "inductance_temperature",
            "viscoelastic_relaxation", "ratchet", "heating_dependent_convection"});
}

TEST_CASE(
    "Every candidate attaches, is the base model at its nested start, and frees real "
    "parameters") {
  const std::string data_path = protocol_record("60 s");
  const Scenario base = base_model(data_path);
  const MeasuredData data = read_measured_data(data_path, *shared_units());
  const Context fitted = base.make_context();
  const auto candidates =
      fit::effect_candidates(base, fitted, data, {"load.force", "muscle.inductance_measure"});
  CHECK(candidates.skipped.empty());
  auto names = candidate_names(candidates);
  std::sort(names.begin(), names.end());
  names.erase(std::unique(names.begin(), names.end()), names.end());
  auto expected = fit::effect_names();
  std::sort(expected.begin(), expected.end());
  CHECK(names == expected);
  const Trace bare = simulate(base);
  for (const auto& candidate : candidates.candidates) {
    INFO(candidate.name << " [" << candidate.member << "]");
    const Scenario augmented = base_model(data_path, candidate.overrides);
    REQUIRE_FALSE(candidate.parameters.empty());
    REQUIRE(candidate.nested.size() == candidate.parameters.size());
    Context nested = augmented.make_context();
    Context inside = augmented.make_context();
    for (std::size_t j = 0; j < candidate.parameters.size(); ++j) {
      const auto& parameter = candidate.parameters[j];
      INFO(parameter.path);
      REQUIRE(augmented.system->parameter_index(parameter.path));
      CHECK(parameter.lower < parameter.upper);
      CHECK(candidate.nested[j] >= parameter.lower);
      CHECK(candidate.nested[j] <= parameter.upper);
      nested.set_parameter(parameter.path, candidate.nested[j]);
      // A tenth of the way from the nested start to the upper bound: the effect at a real size
      // (a ratchet's threshold low enough for the protocol's heating to pass).
      inside.set_parameter(parameter.path,
                           candidate.nested[j] + 0.1 * (parameter.upper - candidate.nested[j]));
    }
    // At its nested start the augmented model is the base model, to the solver's tolerance.
    const Trace start = simulate(augmented, nested);
    REQUIRE(start.time.size() == bare.time.size());
    CHECK(max_abs_difference(start["load/force"], bare["load/force"]) < 1e-5);
    CHECK(max_abs_difference(start["muscle/inductance_measure"],
                             bare["muscle/inductance_measure"]) < 1e-8);
    // With the effect at a real size it changes what the fit compares.
    const Trace sized = simulate(augmented, inside);
    CHECK(max_abs_difference(sized["load/force"], bare["load/force"]) +
              max_abs_difference(sized["muscle/inductance_measure"],
                                 bare["muscle/inductance_measure"]) >
          1e-5);
  }
}

TEST_CASE(
    "A model that carries a family's effect already gets that family's candidates beside it") {
  // A model from an earlier discover (its augmented.yaml): a Dahl element called after its type
  // and a slow branch called after its family. Every candidate attaches under names of its own.
  const std::string data_path = protocol_record("60 s");
  const MeasuredData data = read_measured_data(data_path, *shared_units());
  const std::string carried =
      "muscle.effects=[{type: hysteresis, stiffness: 50 N/m, force: 6 mN}, {type: maxwell_branch, "
      "name: slow_relaxation, stiffness: 1.5 N/m, time_constant: 300 s}]";
  const Scenario base = base_model(data_path, {carried});
  const auto candidates = fit::effect_candidates(base, base.make_context(), data, {"load.force"});
  std::size_t hysteresis = 0, relaxation = 0;
  for (const auto& candidate : candidates.candidates) {
    INFO(candidate.name << " [" << candidate.member << "]");
    const Scenario augmented = base_model(data_path, candidate.overrides);
    for (const auto& parameter : candidate.parameters)
      CHECK(augmented.system->parameter_index(parameter.path));
    // The carried effects stay, with their own names and values.
    CHECK(augmented.system->parameter_index("muscle.effects[0].stiffness"));
    CHECK(augmented.make_context().parameter("muscle.effects[1].time_constant") == 300.0);
    hysteresis += candidate.name == "hysteresis";
    relaxation += candidate.name == "slow_relaxation";
  }
  CHECK(hysteresis >= 2);  // the Dahl element and the Prandtl-Ishlinskii operators
  CHECK(relaxation >= 2);  // one branch and two
}

TEST_CASE("Candidates that cannot attach to a base model are skipped with the reason") {
  const std::string data_path = protocol_record("60 s");
  const MeasuredData data = read_measured_data(data_path, *shared_units());
  SECTION("no compared coil output: no inductance candidate") {
    const Scenario base = base_model(data_path);
    const auto candidates = fit::effect_candidates(base, base.make_context(), data, {"load.force"});
    REQUIRE(candidates.skipped.size() == 1);
    CHECK(candidates.skipped[0].name == "inductance_temperature");
    CHECK_THAT(candidates.skipped[0].reason, Catch::Contains("no output of the coil"));
  }
  SECTION("a reduced form without force_per_kelvin has no temperature for heat terms") {
    const Scenario base = base_model(data_path, {"muscle.thermal_force={form: reduced, kappa_P: "
                                                 "7.2e-3 N/J, kappa_c: 131.6e-3 1/s, "
                                                 "ambient_temperature: 23 degC}"});
    const auto candidates = fit::effect_candidates(base, base.make_context(), data, {"load.force"});
    std::vector<std::string> skipped;
    for (const auto& entry : candidates.skipped) {
      skipped.push_back(entry.name);
      if (entry.name != "inductance_temperature")
        CHECK_THAT(entry.reason, Catch::Contains("reports no temperature"));
    }
    CHECK(skipped == std::vector<std::string>{
                         "nonlinear_convection", "thermal_lag", "temperature_dependent_stiffness",
                         "inductance_temperature", "ratchet", "heating_dependent_convection"});
  }
}

TEST_CASE("A ratchet's threshold starts where the base model's temperature crosses it") {
  // At zero rate a ratchet whose threshold the model never reaches changes nothing for any
  // rate: the fit has no gradient to leave zero size by. Its threshold starts 10 K above
  // ambient, or halfway up a base model that never gets 20 K warmer.
  const std::string data_path = protocol_record("60 s");
  const Scenario base = base_model(data_path);
  const MeasuredData data = read_measured_data(data_path, *shared_units());
  const double ambient = base.make_context().parameter("muscle.thermal_force.ambient_temperature");
  const auto threshold_start = [&](double peak) {
    const auto candidates = fit::effect_candidates(base, base.make_context(), data, {"load.force"},
                                                   {fit::MeasuredRoles{}, peak});
    for (const auto& candidate : candidates.candidates) {
      if (candidate.name != "ratchet") continue;
      for (std::size_t j = 0; j < candidate.parameters.size(); ++j)
        if (candidate.parameters[j].path.ends_with(".threshold")) return candidate.nested[j];
    }
    FAIL("no ratchet threshold among the candidates");
    return 0.0;
  };
  CHECK(threshold_start(0.0) == ambient + 10.0);  // not known: as before
  CHECK(threshold_start(ambient + 40.0) == ambient + 10.0);
  CHECK(threshold_start(ambient + 6.0) == Approx(ambient + 3.0).epsilon(1e-15));
  CHECK(threshold_start(ambient + 19.0) == Approx(ambient + 9.5).epsilon(1e-15));
}

TEST_CASE("Every effect kind is a discover candidate, or is excluded with the reason") {
  // Each effect kind declares with its registration how discover tries it (its families) or
  // why it does not; a kind added without either would never be tried. A declared family's
  // candidates attach that kind.
  const std::string data_path = protocol_record("60 s");
  const Scenario base = base_model(data_path);
  const MeasuredData data = read_measured_data(data_path, *shared_units());
  const auto candidates = fit::effect_candidates(base, base.make_context(), data,
                                                 {"load.force", "muscle.inductance_measure"});
  const KindRegistry kinds = standard_kinds();
  std::vector<std::string> declared_families;
  for (const Kind* kind : kinds.kinds(kEffectCategory)) {
    INFO(kind->name);
    REQUIRE(kind->candidates.has_value());
    const auto& declaration = std::any_cast<const CandidateDeclaration&>(kind->candidates);
    CHECK(declaration.families.empty() != declaration.excluded.empty());
    bool attached = false;
    for (const auto& candidate : candidates.candidates) {
      for (const auto& override : candidate.overrides)
        attached = attached || override.find("type: " + kind->name + ",") != std::string::npos;
    }
    CHECK(attached == !declaration.families.empty());
    for (const auto& family : declaration.families) declared_families.push_back(family.name);
  }
  // The muscle's own coil term is the one family not of an effect kind.
  declared_families.push_back("inductance_temperature");
  std::sort(declared_families.begin(), declared_families.end());
  // A family two kinds declare (thermal_lag: heating_lag and heat_sink) is one name.
  declared_families.erase(std::unique(declared_families.begin(), declared_families.end()),
                          declared_families.end());
  auto names = fit::effect_names();
  std::sort(names.begin(), names.end());
  CHECK(declared_families == names);
}
