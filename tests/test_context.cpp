// The run context: one assembled System, many runs, each with its own parameters and state;
// every numeric parameter addressable by path, set in SI without reading the scenario again.
#include <catch2/catch.hpp>

#include <yaml-cpp/yaml.h>

#include <optional>
#include <thread>

#include "sim/run.h"
#include "tests/support/test_support.h"

using namespace tcpmsim;
using namespace tcpmsim::testing;

namespace {

Trace run(const Scenario& scenario, Context& context) {
  return simulate(scenario, context);
}

void check_identical(const Trace& a, const Trace& b) {
  REQUIRE(a.time == b.time);
  for (const auto& [name, values] : a.channels) {
    INFO(name);
    CHECK(bitwise_equal(values, b[name]));  // an unknown estimate (NaN) included
  }
}

// The scenario path of a parameter: an instance of a plural section is written out.
std::string scenario_path(const std::string& parameter, const std::string& yaml) {
  const YAML::Node root = YAML::Load(yaml);
  const std::string first = parameter.substr(0, parameter.find_first_of(".["));
  if (root[first]) return parameter;
  for (const auto& section : root) {
    if (section.second.IsMap() && section.second[first])
      return section.first.as<std::string>() + "." + parameter;
  }
  return parameter;
}

// A value near `value` the parameter accepts, different from it.
double nudged(const ParameterDeclaration& declared) {
  const double value = declared.value;
  for (const double candidate : {value * (1.0 + 1e-3), value * (1.0 - 1e-3), 1e-4, -1e-4}) {
    if (candidate != value && parameter_problem(declared, candidate).empty()) return candidate;
  }
  FAIL("no nearby value for " << declared.path);
  return value;
}

}  // namespace

TEST_CASE("One System runs in two contexts on two threads, each as it runs alone") {
  // The closed loop: sampled estimator and controller, the Muscle Drive's random artefacts, a
  // step reference. The second context changes a muscle, a gain, the noise and the reference.
  Scenario scenario = load_scenario(source_path("configs/ch7_control/force_steps.yaml"),
                                    {"scenario.duration=60 s"}, shared_units());
  auto configure = [&](Context& context, bool changed) {
    if (!changed) return;
    context.set_parameter("muscle.mechanics.k2", 3.5);
    context.set_parameter("controller.gains.proportional", 400.0);
    context.set_parameter("drive.measurement.timing_noise", 5e-9);
    context.set_parameter("controller.reference.range[1]", 0.5);
  };
  std::vector<Trace> serial;
  for (bool changed : {false, true}) {
    Context context = scenario.make_context();
    configure(context, changed);
    serial.push_back(run(scenario, context));
  }
  CHECK(serial[0]["muscle/force"] != serial[1]["muscle/force"]);
  std::vector<Trace> parallel(2);
  std::vector<std::thread> threads;
  for (int k = 0; k < 2; ++k) {
    threads.emplace_back([&, k] {
      Context context = scenario.make_context();
      configure(context, k == 1);
      parallel[static_cast<std::size_t>(k)] = run(scenario, context);
    });
  }
  for (auto& thread : threads) thread.join();
  check_identical(serial[0], parallel[0]);
  check_identical(serial[1], parallel[1]);
}

TEST_CASE("A context runs its system again from a fresh run state") {
  Scenario scenario = load_scenario(source_path("configs/ch7_control/deflection_steps.yaml"),
                                    {"scenario.duration=30 s"}, shared_units());
  Context context = scenario.make_context();
  const Trace first = run(scenario, context);
  const Trace again = run(scenario, context);
  check_identical(first, again);
  Context copy(context);  // the parameters, not the run
  check_identical(first, run(scenario, copy));
}

TEST_CASE("Every parameter set in a context gives the run of the scenario that states it") {
  // For each parameter of scenarios covering every kind of component and signal: nudge it in a
  // context of the assembled model, and in the scenario's text (resolved: with its defaults
  // stated), and compare the runs bit for bit.
  const std::vector<std::pair<const char*, const char*>> cases{
      {"configs/ch7_identification.yaml", "scenario.duration=20 s"},
      {"configs/ch6_static_staircase.yaml", "scenario.duration=30 s"},
      {"configs/ch6_iron_muscle_lifting_mass.yaml", "scenario.duration=15 s"},
      {"configs/ch7_force_creep.yaml", "scenario.duration=20 s"},
      {"configs/ch7_control/force_steps.yaml", "scenario.duration=50 s"},
      {"configs/ch7_control/deflection_sweep.yaml", "scenario.duration=30 s"},
      {"configs/composition/two_muscles.yaml", "scenario.duration=30 s"},
      {"configs/ch4/st_harmonic_first.yaml", "scenario.duration=0.76 s"}};
  int checked = 0, structural = 0;
  for (const auto& [file, shorter] : cases) {
    const Scenario base = load_scenario(source_path(file), {shorter}, shared_units());
    const std::string text = base.resolved_yaml;
    const Scenario scenario = load_scenario_text(text, file, {}, shared_units());
    for (const auto& parameter : scenario.system->parameters()) {
      if (!parameter.derived_from.empty()) continue;
      const ParameterDeclaration& declared = parameter.declaration;
      const double value = nudged(declared);
      INFO(file << ": " << declared.path << " = " << number(value) << " " << declared.unit);
      Context context = scenario.make_context();
      context.set_parameter(declared.path, value);
      const std::string assignment = scenario_path(declared.path, text) + "=" + number(value) +
                                     (declared.unit == "1" ? "" : " " + declared.unit);
      std::optional<Scenario> stated;
      try {
        stated = build_scenario(ConfigNode::load_text(text, file, {assignment}, shared_units()));
      } catch (const ConfigError&) {
      }
      bool runs = true;
      try {
        scenario.system->prepare(context);
      } catch (const ParameterError&) {
        runs = false;
      }
      if (!stated) {
        // A value the scenario refuses (a temperature dependence without its reference): the
        // run refuses it too.
        CHECK_FALSE(runs);
        ++structural;
        continue;
      }
      if (!runs) {
        // A value the model as built cannot take: the command line builds it into the model.
        const Scenario by_command_line =
            load_scenario_text(text, file, {assignment}, shared_units());
        CHECK(by_command_line.parameter_settings.empty());
        check_identical(simulate(by_command_line), simulate(*stated));
        ++structural;
        continue;
      }
      check_identical(run(scenario, context), simulate(*stated));
      ++checked;
    }
  }
  CHECK(checked > 200);
  CHECK(structural < 10);
}

TEST_CASE(
    "A parameter is set by path in SI, checked at once, and its conditions when a run starts") {
  Scenario scenario =
      load_scenario(source_path("configs/ch7_control/force_steps.yaml"), {}, shared_units());
  Context context = scenario.make_context();
  CHECK(context.parameter("muscle.mechanics.k2") == Approx(2.7));
  CHECK_THROWS_WITH(context.set_parameter("muscle.mechanics.k3", 1.0),
                    "muscle.mechanics.k3: no such parameter");
  CHECK_THROWS_WITH(context.set_parameter("muscle.mechanics.k1", -1.0),
                    "muscle.mechanics.k1: expected a positive value in N/m, got -1 N/m");
  CHECK_THROWS_WITH(
      context.set_parameter("controller.gains.proportional", 0.0),
      "controller.gains.proportional: expected a non-zero gain ((7.8) divides by it)");
  CHECK_THROWS_WITH(context.set_parameter("estimator.sample_period", 0.1),
                    "estimator.sample_period: is derived (1 / drive.pwm_frequency); set what it "
                    "derives from");
  // The estimator's and controller's periods follow the drive's PWM frequency.
  context.set_parameter("drive.pwm_frequency", 25.0);
  scenario.system->prepare(context);
  CHECK(context.parameter("estimator.sample_period") == 1.0 / 25.0);
  CHECK(context.parameter("controller.sample_period") == 1.0 / 25.0);
  // Conditions between parameters are checked when a run starts.
  context.set_parameter("controller.power_limits[0]", 4.0);
  CHECK_THROWS_WITH(scenario.system->prepare(context),
                    Catch::Contains("PID: power limits must satisfy P_min < P_max"));
  context.set_parameter("controller.power_limits[0]", 0.1);
  context.set_parameter("controller.reference.range[0]", 0.6);  // above range[1]
  CHECK_THROWS_WITH(scenario.system->prepare(context),
                    Catch::Contains("controller.reference: expected range lower < upper"));
}

TEST_CASE("A derived parameter meets its declared range when a run starts") {
  // The coil's preload length follows the spring's ends; ends that cross make it negative.
  Scenario scenario =
      load_scenario(source_path("configs/ch4/sa_end_stop_max.yaml"), {}, shared_units());
  Context context = scenario.make_context();
  context.set_parameter("spring.first_end", 0.2);
  CHECK_THROWS_WITH(scenario.system->prepare(context),
                    "spring.inductance.preload_length: expected a positive value in m, got "
                    "-0.078 m (derived: second_end - first_end at the start)");
  context.set_parameter("spring.first_end", 0.002);
  scenario.system->prepare(context);
  CHECK(context.parameter("spring.inductance.preload_length") == 0.122 - 0.002);
}
