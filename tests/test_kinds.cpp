// The registry of kinds: every kind builds from its examples, the listing in
// docs/reference/kinds.md is the one the code produces, and a new kind needs nothing from the
// engine but registration.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "identification/effect_catalogue.h"
#include "models/muscle.h"
#include "sim/kind_listing.h"
#include "sim/parametric_component.h"
#include "tests/support/test_support.h"

using namespace tcpmsim;
using namespace tcpmsim::testing;

namespace {

// The section at a dotted path such as "drive.power" or "muscle.effects[0]".
ConfigNode section_at(const ConfigNode& root, const std::string& path) {
  ConfigNode node = root;
  std::size_t begin = 0;
  while (begin < path.size()) {
    const std::size_t end = std::min(path.find('.', begin), path.size());
    std::string key = path.substr(begin, end - begin);
    const std::size_t bracket = key.find('[');
    node = node.at(key.substr(0, bracket));
    if (bracket != std::string::npos)
      node = node.elements().at(std::stoul(key.substr(bracket + 1)));
    begin = end + 1;
  }
  return node;
}

// The kind a section names: its selector, the category's scalar kind for a bare value, or the
// category's default kind; a category without a selector has one kind.
std::string kind_named(const KindRegistry& kinds, const Category& category,
                       const ConfigNode& section) {
  if (category.selector.empty()) return kinds.kinds(category.name).front()->name;
  if (section.is_scalar()) return category.scalar_kind;
  if (section.has(category.selector)) return section.text(category.selector);
  return category.default_kind;
}

// Every channel finite once known (an estimate is NaN, unknown, until its first measurement).
bool finite_once_known(const Trace& trace) {
  for (const auto& [name, values] : trace.channels) {
    const auto known =
        std::find_if(values.begin(), values.end(), [](double v) { return !std::isnan(v); });
    if (!std::all_of(known, values.end(), [](double v) { return std::isfinite(v); })) return false;
  }
  return true;
}

}  // namespace

TEST_CASE("Every kind of the standard registry builds and runs from its examples") {
  const KindRegistry kinds = standard_kinds();
  int examples = 0;
  for (const Category& category : kinds.categories()) {
    INFO(category.name);
    CHECK_FALSE(kinds.kinds(category.name).empty());
    if (category.selector.empty()) CHECK(kinds.kinds(category.name).size() == 1);
    for (const Kind* kind : kinds.kinds(category.name)) {
      INFO(kind->name);
      REQUIRE_FALSE(kind->examples.empty());
      int naming = 0;  // examples whose section names this kind (others show a section it reads)
      for (const auto& example : kind->examples) {
        INFO(example.node);
        const ExampleScenario where(example, kind->name + "_example.yaml");
        const ConfigNode root =
            ConfigNode::load_text(example.text, where.name(), {}, shared_units());
        naming += kind_named(kinds, category, section_at(root, example.node)) == kind->name;
        const Scenario scenario = load_scenario_text(
            example.text, where.name(), {"scenario.duration=0.01 s"}, shared_units(), kinds);
        // An example is a muscle or spring of the kinds tcpmsim models: nothing implausible.
        CHECK(scenario.warnings == std::vector<std::string>{});
        Context context = scenario.make_context();
        double* state = context.state().data();
        scenario.system->initialize(context, 0.0, state);
        scenario.system->at_breakpoint(context, 0.0, 0.0, state);
        CHECK(scenario.system->check_component_contracts(context, 0.0, state) == "");
        const Trace trace = simulate(scenario);
        CHECK(trace.time.back() == 0.01);
        CHECK(finite_once_known(trace));
        ++examples;
      }
      CHECK(naming >= 1);
    }
  }
  CHECK(examples > 25);
}

TEST_CASE("docs/reference/kinds.md is the listing the registry produces") {
  std::ifstream file(source_path("docs/reference/kinds.md"));
  std::stringstream written;
  written << file.rdbuf();
  // Regenerate with: build/tcpmsim kinds --markdown > docs/reference/kinds.md
  CHECK(written.str() ==
        describe_kinds(standard_kinds(), shared_units(), true, fit::describe_candidates));
}

TEST_CASE("The listing says which choice or which other key makes a key required") {
  const KindRegistry& kinds = standard_kinds();
  const auto required_with = [&](const std::string& category, const std::string& name) {
    std::map<std::string, std::string> keys;
    for (const auto& key : kind_keys(kinds, kinds.registered(category, name), shared_units()))
      keys[key.key] = key.fallback.empty() && !key.optional ? key.required_with : "not required";
    return keys;
  };
  // A Joule drive heats by power, duty or current: each mode reads its own command (and the
  // duty mode the supply it switches), so of power, duty and current one is required.
  const auto joule = required_with("drive", "joule");
  CHECK(joule.at("mode") == "");
  CHECK(joule.at("power") == "mode: power");
  CHECK(joule.at("duty") == "mode: duty");
  CHECK(joule.at("supply_voltage") == "mode: duty");
  CHECK(joule.at("current") == "mode: current");
  // A bundle's members have their own drives only when wired individually. Its examples also
  // differ in how a member's resistance is given, but the wiring, a choice of another section,
  // does not decide that.
  // A multisine is scaled to a range or given an offset and an amplitude: of the two, one.
  std::map<std::string, std::string> without;
  for (const auto& key : kind_keys(kinds, kinds.registered("signal", "multisine"), shared_units()))
    without[key.key] = key.required_without;
  CHECK(without.at("offset") == "range");
  CHECK(without.at("amplitude") == "range");
  CHECK(without.at("components") == "");
  // Keys asked for with has() are optional unless another replaces them: a hysteresis element is
  // given by its force or by its radius, a Maxwell branch by its damping or its time constant;
  // a softening's slope and bend, and a convection's exponent, are optional wherever read.
  const auto status = [&](const std::string& name) {
    std::map<std::string, std::string> keys;
    for (const auto& key : kind_keys(kinds, kinds.registered("effect", name), shared_units())) {
      keys[key.key] = !key.fallback.empty() ? "default"
                      : key.optional        ? "optional"
                                            : "required without " + key.required_without;
    }
    return keys;
  };
  CHECK(status("hysteresis").at("force") == "required without radius");
  CHECK(status("hysteresis").at("radius") == "required without force");
  CHECK(status("maxwell_branch").at("damping") == "required without time_constant");
  CHECK(status("maxwell_branch").at("time_constant") == "required without damping");
  CHECK(status("thermal_softening").at("stiffness_slope") == "optional");
  CHECK(status("thermal_softening").at("stiffness_curvature") == "optional");
  CHECK(status("free_convection").at("exponent") == "optional");
  const auto bundle = required_with("bundle", "parallel");
  CHECK(bundle.at("electrical.drive.supply_voltage") == "electrical.wiring: individual");
  CHECK(bundle.at("muscle.resistance.resistance") == "");
  CHECK(bundle.at("count") == "");
}

namespace {

// A kind the standard registry does not have, written as a user would: a linear
// "parallel_spring" effect (F = s x with no state), its builder, its registration.
struct ParallelSpringParameters {
  double stiffness = 0.0;
};

class ParallelSpring final : public ParametricComponent<ParallelSpringParameters> {
 public:
  using ParametricComponent::ParametricComponent;
  std::vector<OutputDeclaration> outputs() const override {
    return {{"stiffness", "N/m", false, false},
            {"offset_force", "N", false, false},
            {"rest_stiffness", "N/m", false, false},
            {"rest_force", "N", false, false}};
  }
  void compute_outputs(const Evaluation& e) const override {
    set_output(e, 0, run_parameters(e).stiffness);
    set_output(e, 1, 0.0);
    set_output(e, 2, run_parameters(e).stiffness);  // elastic: the same at rest
    set_output(e, 3, 0.0);
  }
};

void attach_parallel_spring(const ConfigNode& section, const MuscleAttachment& muscle,
                            ScenarioBuilder& build) {
  using P = ParallelSpringParameters;
  section.declare({"type", "stiffness"});
  P p;
  ParameterBindings<P> bind;
  bind.quantity(section, "stiffness", "N/m", ValueCheck::positive(), p, bind.member(&P::stiffness));
  build.system().add(
      std::make_unique<ParallelSpring>(muscle.group, "parallel_spring", p, std::move(bind)));
  build.system().connect(muscle.muscle + ".attached_stiffness", muscle.group + ".stiffness");
  build.system().connect(muscle.muscle + ".attached_force", muscle.group + ".offset_force");
  build.system().connect(muscle.muscle + ".attached_rest_stiffness",
                         muscle.group + ".rest_stiffness");
  build.system().connect(muscle.muscle + ".attached_rest_force", muscle.group + ".rest_force");
}

}  // namespace

TEST_CASE("A kind added outside the engine is built by name, its parameters addressable") {
  KindRegistry kinds = standard_kinds();
  kinds.add({kEffectCategory,
             "parallel_spring",
             "a spring in parallel with the SLS",
             {},
             EffectBuilder(attach_parallel_spring)});
  const std::string yaml = R"(scenario: {name: test, duration: 5 s}
output: {rate: 10 Hz}
muscle:
  thermal_force: {form: reduced, kappa_P: 7.2e-3 N/J, kappa_c: 131.6e-3 1/s, ambient_temperature: 23 degC}
  mechanics: {k1: 10.8 N/m, k2: 2.7 N/m, damping: 4.3 N*s/m, force_offset: 0.1 N}
  resistance: 10 ohm
  inductance: {quantity: measure, lambda_l: 2.81 mm, lambda_x: 28.8 mm, lambda_0: 0.433}
  effects: [{type: parallel_spring, stiffness: 4 N/m}]
drive: {mode: power, power: 0 W}
load: {type: force, force: 0.4 N}
)";
  const Scenario scenario = load_scenario_text(yaml, "test.yaml", {}, shared_units(), kinds);
  const Trace trace = simulate(scenario);
  // At rest under 0.4 N with the dashpot relaxed: (k1 + s) x = F - phi_0, from the start on.
  CHECK(trace["muscle/deflection"].front() == Approx((0.4 - 0.1) / (10.8 + 4.0)).epsilon(1e-12));
  CHECK(trace["muscle/deflection"].back() == Approx((0.4 - 0.1) / (10.8 + 4.0)).epsilon(1e-9));
  Context context = scenario.make_context();
  CHECK(context.parameter("muscle.effects[0].stiffness") == 4.0);
  // The standard registry does not know it.
  CHECK_THROWS_WITH(
      scenario_from_text(yaml),
      Catch::Contains(
          "muscle.effects[0].type: expected one of maxwell_branch, "
          "free_convection, thermal_softening, hysteresis, nonlinear_stiffness, thermal_lag, "
          "heating_lag, heat_sink, ratchet, heating_convection, "
          "got 'parallel_spring'"));
}
