// tcpmsim discover's verdicts on whole runs over every candidate (issue 28): none on data
// without an effect, every candidate nesting the base model, unexplained where no candidate
// explains the residual, the two effects of the real measurement named, and --max-effects going
// on from the model a run wrote. The longest
// specifications of the suite (about four minutes in Release): the sanitizer tree leaves this
// file out (TCPMSIM_TEST_EXCLUDE_FILES in .ci/run), and runs discover's pieces and one whole
// discover (test_discover.cpp) instead.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>

#include "identification/discovery.h"
#include "identification/discovery_diagnostics.h"
#include "identification/discovery_report.h"
#include "identification/discovery_runs.h"
#include "sim/value_check.h"
#include "tests/support/discover_data.h"
#include "tests/support/test_support.h"

using namespace tcpmsim;
using namespace tcpmsim::testing;

TEST_CASE("Data without a hidden effect give the verdict none") {
  const std::string data = discover_measurement("null", {});
  const auto setup = fit::setup_discovery(
      discover_request(data, {"hysteresis", "slow_relaxation", "nonlinear_stiffness"}),
      shared_units());
  const fit::Discovery found = fit::discover(setup);
  INFO(fit::discovery_summary(found));
  CHECK(found.verdict == "none");
  CHECK(found.kind == fit::VerdictKind::none);
  // The base model fits to the noise, and its residual is white: at the floor read from the
  // data, the load cell's sqrt(1 + 0.5^2/12) = 1.01 mN.
  CHECK(found.at_noise == std::vector<bool>{true});
  CHECK(found.setup.floor[0] == Approx(1.01e-3).epsilon(0.05));
  CHECK(found.base.validation.rmse[0] < 1.2e-3);
  CHECK(found.diagnostics.outputs[0].whiteness.p_value > 1e-3);
  for (const auto& candidate : found.candidates) {
    CHECK_FALSE(candidate.significant);
    // White noise is what each leaves: its samples count in full (lag-1 autocorrelation within
    // 4 standard errors, 4 / sqrt(1600), of zero).
    if (candidate.status == "fitted") CHECK(candidate.evidence_shares[0] > 0.8);
  }
  // A white residual needs no word beyond the verdict; one that is not white (as real data's
  // is: no model is the data's law) gets the size of its structured part,
  // sqrt(rmse^2 - floor^2), its share of the floor and what it follows, so that none is not
  // read as "the residual is noise".
  CHECK_THAT(fit::discovery_report(found), !Catch::Contains("is not white"));
  fit::Discovery coloured = found;
  coloured.diagnostics.outputs[0].whiteness.p_value = 2e-5;
  const double rest = fit::structured_rms(found.base.validation.rmse[0], found.setup.floor[0]);
  const std::string report = fit::discovery_report(coloured);
  CHECK_THAT(report, Catch::Contains("The force residual is not white (Ljung-Box p = 2e-05): a "
                                     "structured part of about " +
                                     number_text(rest, 3) + " N RMS (" +
                                     number_text(100 * rest / found.setup.floor[0], 3) +
                                     " % of the floor)"));
  CHECK_THAT(report, Catch::Contains("It follows, strongest first: "));
}

TEST_CASE("Every candidate nests the base model: its refit ends at or below the base fit's cost") {
  // Each candidate starts from the base fit with its effect at zero size, where it is the base
  // model; its cost there equals the base fit's within the solver's tolerance (more states change
  // CVODE's steps: at rtol 1e-6 by some 0.1 of a cost of 640, below the half unit that moves the
  // BIC by one), and its fit only goes down from there.
  for (const auto& [name, hidden] : std::vector<std::pair<std::string, std::vector<std::string>>>{
           {"nest_null", {}},
           {"nest_play",
            {"muscle.effects=[{type: hysteresis, name: a, stiffness: 4 N/m, radius: 0.8 mm}, "
             "{type: hysteresis, name: b, stiffness: 1.5 N/m, radius: 4 mm}]"}}}) {
    const std::string data = discover_measurement(name, hidden, "100 s");
    fit::DiscoverRequest all = discover_request(data, {});
    all.validate_from = 70.0;
    all.max_order = 0;
    const fit::Discovery found = fit::discover(fit::setup_discovery(all, shared_units()));
    INFO(name << "\n" << fit::discovery_summary(found));
    CHECK(found.candidates.size() >= 8);
    if (hidden.empty()) CHECK(found.at_noise == std::vector<bool>{true});
    for (const auto& candidate : found.candidates) {
      INFO(candidate.name << " [" << candidate.member << "]: " << candidate.reason);
      REQUIRE(candidate.status == "fitted");
      CHECK(std::abs(candidate.nested_cost - found.base.cost) < 0.5);
      CHECK(candidate.result.cost <= candidate.nested_cost * (1 + 1e-9));
      CHECK(candidate.result.cost < found.base.cost + 0.5);
      // So its BIC can rise by no more than the parameters it adds cost.
      const double n = static_cast<double>(found.base.identification.samples);
      const auto added = candidate.result.estimates.size() - found.base.estimates.size();
      CHECK(candidate.delta_bic < static_cast<double>(added) * std::log(n) + 1.0);
      // Where the base model misses no output beyond the noise, a candidate that found nothing
      // from its nested start has nothing to find: it is not fitted again from a drawn start
      // (without this gate null data cost 654 simulations against 407).
      if (hidden.empty()) CHECK_FALSE(candidate.retried_from_drawn);
    }
  }
}

TEST_CASE("A residual no candidate explains is unexplained, never none, and --set reaches it") {
  // Hysteresis in the data, but only a thermal candidate tried: the base model misses by several
  // times the floor, the candidate does not help, and the verdict says so.
  const std::string data = discover_measurement(
      "unexplained", {"muscle.effects=[{type: hysteresis, stiffness: 50 N/m, force: 6 mN}]"});
  fit::DiscoverRequest thermal = discover_request(data, {"thermal_lag"});
  thermal.overrides = {"muscle.inductance.lambda_0=0.5"};
  const fit::Discovery found = fit::discover(fit::setup_discovery(thermal, shared_units()));
  INFO(fit::discovery_summary(found));
  CHECK(found.verdict == "unexplained");
  CHECK(found.kind == fit::VerdictKind::unexplained);
  CHECK(found.at_noise == std::vector<bool>{false});
  CHECK(found.base.validation.rmse[0] > 2 * found.setup.floor[0]);
  CHECK(found.gap_closed == 0.0);
  // The report ranks what the residual follows: the direction of the last motion among the
  // strongest.
  const auto ranked = fit::ranked_signatures(found.diagnostics, 0);
  REQUIRE(ranked.size() >= 3);
  bool direction = false;
  for (std::size_t i = 0; i < 3; ++i)
    direction = direction || ranked[i].what.find("last direction of motion") != std::string::npos;
  CHECK(direction);
  CHECK(fit::discovery_report(found).find("**unexplained**") != std::string::npos);
  CHECK(fit::discovery_json(found).find("\"verdict_kind\": \"unexplained\"") != std::string::npos);
  // The model's --set reaches every candidate's refit, not the base fit alone.
  for (const auto& candidate : found.candidates) {
    const Context context = candidate.spec.problem.model->make_context();
    CHECK(context.parameter("muscle.inductance.lambda_0") == 0.5);
  }
}

TEST_CASE("A ratchet and a heating-driven convection in the data are named, each as itself") {
  // The two effects a real TCPM measurement showed: a force lost for good above a threshold
  // temperature, and an hA that rises while the heater runs. Each is named against the other;
  // against the whole catalogue (a slow relaxation also drifts) in the hidden-effect matrices.
  const std::vector<std::string> tried = {"ratchet", "heating_dependent_convection"};
  for (const auto& [name, hidden] : std::vector<std::pair<std::string, std::string>>{
           {"ratchet", "muscle.effects=[{type: ratchet, rate: 1e-5 N/(K*s), threshold: 33 degC}]"},
           {"heating_dependent_convection",
            "muscle.effects=[{type: heating_convection, conductance: 0.04 W/K, reference_power: "
            "3 W}]"}}) {
    // 200 s of multisines: 150 s to identify, 50 s to validate.
    const std::string data = discover_measurement("new_" + name, {hidden}, "200 s");
    fit::DiscoverRequest two = discover_request(data, tried);
    two.validate_from = 150.0;
    const fit::Discovery found = fit::discover(fit::setup_discovery(two, shared_units()));
    INFO(fit::discovery_summary(found));
    CHECK(found.verdict == name);
    CHECK(found.gap_closed > 0.6);
  }
}

TEST_CASE("A candidate that never leaves its nested start is fitted again from a drawn start") {
  // The truth of the own matrix's case nonlinear_stiffness_1mN_seed2 (scripts/discover_matrix.py)
  // with its knee at 22 mm instead of 24 mm (at 24 mm the refit has found the knee from zero
  // size since fits' sensitivities ride on the state's steps). At zero size the knee's position
  // and width change nothing, so their gradient is zero; its multistart finds the nested start
  // cheapest, and the refit from there never moves. Refined from its best drawn start as well,
  // the knee is found and named.
  const std::string data = discover_measurement(
      "stuck_knee",
      {"muscle.thermal_force.kappa_P=0.007514203142 N/J",
       "muscle.thermal_force.kappa_c=0.145634812 1/s", "muscle.mechanics.k1=11.60626624 N/m",
       "muscle.mechanics.k2=2.875412958 N/m", "muscle.mechanics.damping=3.881716722 N*s/m",
       "muscle.mechanics.force_offset=0.09216824015 N",
       "muscle.effects=[{type: nonlinear_stiffness, stiffness: 3.2210568275994635 N/m, "
       "knee_deflection: 22 mm, knee_width: 1 mm}]"},
      "620 s", 2);
  fit::DiscoverRequest knee = discover_request(data, {"nonlinear_stiffness"});
  knee.validate_from = 400.0;
  knee.starts = 8;
  knee.max_order = 0;
  knee.outputs = {"force", "inductance_measure"};
  const fit::Discovery found = fit::discover(fit::setup_discovery(knee, shared_units()));
  INFO(fit::discovery_summary(found));
  CHECK(found.verdict == "nonlinear_stiffness");
  CHECK(found.gap_closed > 0.9);
  bool kept = false;
  for (const auto& candidate : found.candidates) {
    INFO(candidate.member << ": nested cost " << candidate.nested_cost << ", cost "
                          << candidate.result.cost);
    CHECK(candidate.result.cost <= candidate.nested_cost * (1 + 1e-9));
    kept = kept || candidate.drawn_kept;
  }
  CHECK(kept);
}

// --max-effects: a run whose model with the named effect still misses the floor is followed by a
// run from the model it wrote. A floor given at a fifth of the bench's 1 mN noise makes every
// model miss, so the second run comes on data with one effect (the short record of "A short
// discover goes through every stage").
TEST_CASE("A run whose effect still misses the floor is followed by one from the model it wrote") {
  auto request = short_hysteresis_request();
  request.noise = {"force=0.2 mN"};
  const std::string out = process_directory("discover_effects");
  std::vector<fit::Discovery> seen;
  const auto runs =
      fit::discover_effects(fit::setup_discovery(request, shared_units()), 2, out,
                            [&](const fit::Discovery& discovery, const std::string& directory) {
                              fit::write_discovery(directory, discovery);
                              seen.push_back(discovery);
                            });
  INFO(fit::effect_runs_summary(runs, 2));
  REQUIRE(runs.size() == 2);
  REQUIRE(seen.size() == 2);
  CHECK(runs[0].verdict == "hysteresis");
  CHECK(runs[0].directory == out);
  // The named effect's parameters as its refit freed them, which a joint refit frees again.
  REQUIRE(runs[0].effect_parameters.size() == 2);
  CHECK(runs[0].effect_parameters[0].path == "muscle.effects[0].stiffness");
  CHECK(runs[0].effect_parameters[1].path == "muscle.effects[0].radius");
  // A later run's effect comes after the ones its model carries.
  for (const auto& parameter : runs[1].effect_parameters)
    CHECK_THAT(parameter.path, Catch::StartsWith("muscle.effects[1]."));
  CHECK(runs[1].directory == out + "/effect2");
  const std::string first_model = out + "/augmented.yaml";
  CHECK(runs[1].model == first_model);
  CHECK(seen[1].setup.request.model_file == first_model);
  CHECK(seen[1].setup.request.data_file == request.data_file);
  // The second run's base model is the first's augmented model, refitted from its values: on
  // the one output, its identification error is no larger than the augmented fit's.
  const auto& augmented = seen[0].candidates.front().result;
  CHECK(seen[1].base.identification.rmse[0] <= augmented.identification.rmse[0] * (1.0 + 1e-6));
  // Every candidate of the second run joins the effect it carries, its own family's beside it.
  REQUIRE(!seen[1].candidates.empty());
  for (const auto& candidate : seen[1].candidates) {
    CHECK(candidate.status == "fitted");
    CHECK_THAT(candidate.spec.problem.model->resolved_yaml, Catch::Contains("hysteresis_2"));
  }
  CHECK(std::filesystem::exists(out + "/effect2/discovery.json"));
  // effects.json names the model that carries what was found, and that file was written.
  const std::string model =
      runs[1].named ? out + "/effect2/augmented.yaml" : out + "/effect2/baseline.yaml";
  CHECK_THAT(fit::effect_runs_json(runs, 2), Catch::Contains("\"model\": \"" + model + "\""));
  CHECK(std::filesystem::exists(model));
}
