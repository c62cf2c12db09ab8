// discover's catalogue of named effects: every candidate attaches to the chapter-7 base model,
// runs, and frees parameters that exist with bounds around its start; what cannot attach says
// why.
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>

#include "identification/effect_catalogue.h"
#include "sim/run.h"
#include "tests/support/test_support.h"

using namespace tcpmsim;
using namespace tcpmsim::testing;

namespace {

Scenario base_model(const std::string& data, std::vector<std::string> overrides = {}) {
  overrides.push_back("measurement.file=" + data);
  overrides.push_back("scenario.duration=60 s");
  return load_scenario(source_path("configs/discover/ch7_base.yaml"), overrides, shared_units());
}

std::vector<std::string> names_of(const fit::Candidates& candidates) {
  std::vector<std::string> names;
  for (const auto& candidate : candidates.candidates) names.push_back(candidate.name);
  return names;
}

}  // namespace

TEST_CASE("The catalogue names the eight effects of the discovery workflow exactly") {
  CHECK(fit::effect_names() ==
        std::vector<std::string>{"slow_relaxation", "hysteresis", "nonlinear_convection",
                                 "thermal_lag", "nonlinear_stiffness",
                                 "temperature_dependent_stiffness", "inductance_temperature",
                                 "viscoelastic_relaxation"});
}

TEST_CASE("Every candidate attaches to the chapter-7 base model, runs, and frees real parameters") {
  const std::string data_path = protocol_record("60 s");
  const Scenario base = base_model(data_path);
  const MeasuredData data = read_measured_data(data_path, *shared_units());
  const Context fitted = base.make_context();
  const auto candidates =
      fit::effect_candidates(base, fitted, data, {"load.force", "muscle.inductance_measure"});
  CHECK(candidates.skipped.empty());
  auto names = names_of(candidates);
  auto expected = fit::effect_names();
  std::sort(names.begin(), names.end());
  std::sort(expected.begin(), expected.end());
  CHECK(names == expected);
  const Trace bare = simulate(base);
  for (const auto& candidate : candidates.candidates) {
    INFO(candidate.name);
    std::vector<std::string> overrides = candidate.overrides;
    overrides.push_back("measurement.file=" + data_path);
    overrides.push_back("scenario.duration=60 s");
    const Scenario augmented =
        load_scenario(source_path("configs/discover/ch7_base.yaml"), overrides, shared_units());
    const Context context = augmented.make_context();
    REQUIRE_FALSE(candidate.parameters.empty());
    for (const auto& parameter : candidate.parameters) {
      INFO(parameter.path);
      REQUIRE(augmented.system->parameter_index(parameter.path));
      CHECK(parameter.lower < parameter.upper);
      CHECK(context.parameter(parameter.path) >= parameter.lower);
      CHECK(context.parameter(parameter.path) <= parameter.upper);
    }
    // At its start the augmented model runs over the protocol and changes the force.
    const Trace trace = simulate(augmented);
    CHECK(trace.time.size() == bare.time.size());
    if (candidate.name != "inductance_temperature" &&
        candidate.name != "temperature_dependent_stiffness") {
      CHECK(max_abs_difference(trace["load/force"], bare["load/force"]) > 1e-6);
    }
  }
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
    CHECK(skipped == std::vector<std::string>{"nonlinear_convection", "thermal_lag",
                                              "temperature_dependent_stiffness",
                                              "inductance_temperature"});
  }
}
