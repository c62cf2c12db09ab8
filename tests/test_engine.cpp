// The engine: assembly, ordering, breakpoints, sparsity, linear solvers, failures, determinism.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "sim/run.h"
#include "sim/sampled_component.h"
#include "tests/support/test_support.h"

using namespace tcpmsim;
using namespace tcpmsim::testing;

namespace {

// y' = -y / tau, or y' = y^2 (finite-time blow-up at 1/y0), or a NaN derivative after t_bad.
class TestState final : public Component {
 public:
  enum class Law { decay, blowup, nan_after };
  TestState(std::string group, Law law, double initial, double t_bad = 0.0)
      : Component(std::move(group), "test_state"), law_(law), initial_(initial), t_bad_(t_bad) {}
  std::vector<StateDeclaration> states() const override { return {{"value", "1", 1e-12}}; }
  std::vector<OutputDeclaration> outputs() const override { return {{"value", "1"}}; }
  void initialize(const Evaluation&, std::span<double> own) const override { own[0] = initial_; }
  void compute_outputs(const Evaluation& e) const override { set_output(e, 0, state(e, 0)); }
  void compute_derivatives(const Evaluation& e, double* d) const override {
    const double y = state(e, 0);
    switch (law_) {
      case Law::decay:
        set_derivative(d, 0, -y);
        break;
      case Law::blowup:
        set_derivative(d, 0, y * y);
        break;
      case Law::nan_after:
        set_derivative(d, 0, e.time > t_bad_ ? std::numeric_limits<double>::quiet_NaN() : -y);
        break;
    }
  }

 private:
  Law law_;
  double initial_, t_bad_;
};

// Reads an input (feedthrough or not) and republishes it.
class Relay final : public Component {
 public:
  Relay(std::string group, bool feedthrough)
      : Component(std::move(group), "relay"), feedthrough_(feedthrough) {}
  std::vector<OutputDeclaration> outputs() const override { return {{"value", "1"}}; }
  std::vector<InputDeclaration> inputs() const override { return {{"in", feedthrough_}}; }
  void compute_outputs(const Evaluation& e) const override { set_output(e, 0, input(e, 0)); }

 private:
  bool feedthrough_;
};

class Collector final : public OutputSink {
 public:
  void record(double time, std::span<const double> signals) override {
    times.push_back(time);
    values.push_back(signals[0]);
  }
  std::vector<double> times, values;
};

std::string failure_of(SystemBuilder& builder, double t_end) {
  const auto system = builder.build();
  Context context(*system);
  Collector sink;
  Integrator integrator(*system, context, {});
  try {
    integrator.run(0.0, t_end, 0.1, sink);
  } catch (const SolverFailure& failure) {
    return failure.what();
  }
  return "no failure";
}

}  // namespace

TEST_CASE("An unconnected input, an unknown source and an algebraic loop are assembly errors") {
  {
    SystemBuilder system;
    system.add(std::make_unique<Relay>("a", true));
    CHECK_THROWS_WITH(system.build(), "a/relay input 'in' is not connected");
  }
  {
    SystemBuilder system;
    auto& relay = system.add(std::make_unique<Relay>("a", true));
    system.connect(relay, "in", "nowhere.value");
    CHECK_THROWS_WITH(system.build(), "no component publishes 'nowhere.value' (needed by a/relay)");
  }
  {
    SystemBuilder system;
    auto& a = system.add(std::make_unique<Relay>("a", true));
    auto& b = system.add(std::make_unique<Relay>("b", true));
    system.connect(a, "in", "b.value");
    system.connect(b, "in", "a.value");
    CHECK_THROWS_WITH(system.build(),
                      "algebraic loop through direct-feedthrough inputs: a/relay b/relay");
  }
  {
    SystemBuilder system;
    system.add(std::make_unique<TestState>("a", TestState::Law::decay, 1.0));
    system.add(std::make_unique<TestState>("b", TestState::Law::decay, 1.0));
    auto& relay = system.add(std::make_unique<Relay>("c", true));
    system.connect(relay, "in", "a.value");
    system.connect(relay, "in", "b.value");
    CHECK_THROWS_WITH(system.build(), "c/relay input 'in' takes one source, but 2 are connected");
  }
}

TEST_CASE("Components are evaluated after the outputs they read through feedthrough") {
  SystemBuilder builder;
  auto& last = builder.add(std::make_unique<Relay>("c", true));  // added first, must run last
  auto& middle = builder.add(std::make_unique<Relay>("b", true));
  builder.add(std::make_unique<TestState>("a", TestState::Law::decay, 2.0));
  builder.connect(last, "in", "b.value");
  builder.connect(middle, "in", "a.value");
  const auto system = builder.build();
  Context context(*system);
  system->initialize(context, 0.0, context.state().data());
  CHECK(context.signals()[static_cast<std::size_t>(system->signal_index("c.value"))] == 2.0);
}

TEST_CASE("A cycle that passes through a non-feedthrough input is not a loop") {
  // The thermal node and a temperature-dependent drive: each reads the other.
  CHECK_NOTHROW(scenario_from_text(
      physical_muscle_yaml(),
      {"drive={mode: duty, supply_voltage: 7 V, series_resistance: 0.5 ohm, duty: 0.5}",
       "muscle.resistance={form: thermal, resistance: 9 ohm, temperature_coefficient: 6.41e-3 1/K, "
       "reference_temperature: 20 degC}"}));
}

TEST_CASE("The Jacobian pattern follows the wiring") {
  Scenario scenario = scenario_from_text(physical_muscle_yaml());
  const SparsityPattern pattern = scenario.system->jacobian_pattern();
  // States: muscle.temperature (0), muscle.dashpot_extension (1). The dashpot does not depend
  // on temperature at imposed deflection, and the temperature does not depend on the dashpot.
  REQUIRE(pattern.size == 2);
  CHECK(pattern.rows_of_column[0] == std::vector<int>{0});
  CHECK(pattern.rows_of_column[1] == std::vector<int>{1});
  CHECK(pattern.upper_bandwidth() == 0);
  CHECK(pattern.lower_bandwidth() == 0);
  CHECK(pattern.column_groups().size() == 1);
  // Under an imposed force the deflection depends on F_T, so the dashpot row reads T.
  Scenario force = scenario_from_text(physical_muscle_yaml(), {"load={type: force, force: 0.3 N}"});
  const SparsityPattern coupled = force.system->jacobian_pattern();
  CHECK(coupled.rows_of_column[0] == std::vector<int>{0, 1});
}

TEST_CASE("Dense, band and KLU linear solvers give the same trajectory") {
  const std::string config = source_path("configs/ch7_identification.yaml");
  auto run = [&](const std::string& solver) {
    Scenario scenario = load_scenario(
        config, {"solver.linear_solver=" + solver, "solver.rtol=1e-8"}, shared_units());
    return simulate(scenario);
  };
  const Trace dense = run("dense"), band = run("band"), klu = run("klu");
  // The linear solver changes only the Newton iterations' rounding: agreement well within the
  // integration error, 50 rtol times the force scale (0.5 N).
  const double allowed = 50 * 1e-8 * 0.5;
  CHECK(max_abs_difference(dense["muscle/force"], band["muscle/force"]) < allowed);
  CHECK(max_abs_difference(dense["muscle/force"], klu["muscle/force"]) < allowed);
  CHECK(klu.statistics.jacobian_evaluations > 0);
}

TEST_CASE("On the coil-spring chain the three linear solvers share one Newton history") {
  // 52 windings, each pulled by its neighbours: with the state ordered (x_i, v_i) per winding,
  // the Jacobian is banded with half-bandwidth 2, so a difference quotient needs 5 column
  // groups. Under BDF every solver factors the same Jacobian; only its assembly differs. The
  // Newton iterations, step for step, must then be the same, and the windings agree to within
  // rounding, 1e-12 of the 0.23 m spring.
  auto run = [&](const std::string& solver) {
    return simulate(
        load_scenario(source_path("configs/ch4/st_heel_strike.yaml"),
                      {"solver.method=bdf", "solver.linear_solver=" + solver,
                       "scenario.duration=20 ms", "output.start=0 s", "output.rate=5 kHz"},
                      shared_units()));
  };
  const Trace dense = run("dense"), band = run("band"), klu = run("klu");
  for (const Trace* other : {&band, &klu}) {
    CHECK(other->statistics.steps == dense.statistics.steps);
    CHECK(other->statistics.nonlinear_iterations == dense.statistics.nonlinear_iterations);
    CHECK(other->statistics.jacobian_evaluations == dense.statistics.jacobian_evaluations);
    for (const char* winding : {"spring/winding_01", "spring/winding_26", "spring/winding_52"})
      CHECK(max_abs_difference(dense[winding], (*other)[winding]) < 1e-12 * 0.23);
  }
  CHECK(band.statistics.rhs_evaluations_for_jacobian == 5 * band.statistics.jacobian_evaluations);
  CHECK(dense.statistics.rhs_evaluations_for_jacobian ==
        2 * 52 * dense.statistics.jacobian_evaluations);
}

TEST_CASE("Warm restarts follow the cold trajectory to within the integration error") {
  // A closed loop restarted at every 20 Hz sample (the Muscle Drive, the estimator, the PID),
  // without the timer's quantisation, noise and spikes: a rounding-level change then stays one
  // instead of flipping a quantised reading. Warm restarts carry the step size and the Jacobian
  // over each breakpoint; what they change is the error the tolerance allows, not the solution.
  const std::vector<std::string> common{
      "scenario.duration=60 s", "solver.rtol=1e-8", "drive.measurement.timer_resolution=0 s",
      "drive.measurement.timing_noise=0 s", "drive.measurement.spike_probability=0"};
  auto run = [&](const std::string& solver, const std::string& restart) {
    std::vector<std::string> overrides = common;
    overrides.push_back("solver.linear_solver=" + solver);
    overrides.push_back("solver.restart=" + restart);
    return simulate(load_scenario(source_path("configs/ch7_control/deflection_steps.yaml"),
                                  overrides, shared_units()));
  };
  const Trace cold = run("dense", "cold"), warm = run("dense", "warm"), klu = run("klu", "warm");
  REQUIRE(cold.statistics.segments > 1000);
  // 50 rtol times the scales: 0.5 N of force, 30 mm of deflection.
  for (const Trace* other : {&warm, &klu}) {
    CHECK(max_abs_difference(cold["muscle/force"], (*other)["muscle/force"]) < allowed(1e-8, 0.5));
    CHECK(max_abs_difference(cold["muscle/deflection"], (*other)["muscle/deflection"]) <
          allowed(1e-8, 30e-3));
  }
  // Cold computes a Jacobian at every restart; warm only every 51 steps (CVODE's reuse limit),
  // and starts each segment at the last step size instead of estimating one from scratch.
  CHECK(cold.statistics.jacobian_evaluations >= cold.statistics.segments);
  CHECK(warm.statistics.jacobian_evaluations * 5 < cold.statistics.jacobian_evaluations);
  CHECK(warm.statistics.jacobian_evaluations >= warm.statistics.steps / 102);
  CHECK(warm.statistics.rhs_evaluations < cold.statistics.rhs_evaluations);
}

TEST_CASE(
    "Outputs are sampled on the uniform grid, including the end, without a solver stop per "
    "sample") {
  const Trace trace =
      simulate(physical_muscle_yaml(), {"scenario.duration=10.05 s", "output.rate=10 Hz"});
  REQUIRE(trace.time.size() == 102);  // 0, 0.1, ..., 10.0, and 10.05
  CHECK(trace.time[37] == Approx(3.7).epsilon(1e-15));
  CHECK(trace.time.back() == 10.05);
  CHECK(trace.statistics.segments == 1);
  CHECK(trace.statistics.steps < 100);  // far fewer steps than samples: interpolated outputs
}

TEST_CASE("The integrator stops at every breakpoint and counts one segment per stop") {
  // The progress observer hears the time every step reaches: each step of the power must be
  // one of them exactly, so that no step integrates across a discontinuity.
  Scenario scenario = scenario_from_text(
      physical_muscle_yaml(),
      {"drive.power={type: steps, initial: 0 W, times: [10 s, 20 s, 30.5 s], values: [1 W, 2 W, "
       "0 W]}"});
  MemorySink outputs(*scenario.system);
  std::vector<double> reached;
  const SolverStatistics statistics =
      integrate(scenario, outputs, [&](double time, long) { reached.push_back(time); });
  for (double breakpoint : {10.0, 20.0, 30.5}) {
    INFO("breakpoint at " << breakpoint << " s");
    CHECK(std::find(reached.begin(), reached.end(), breakpoint) != reached.end());
  }
  CHECK(std::is_sorted(reached.begin(), reached.end()));
  CHECK(reached.back() == 100.0);
  CHECK(statistics.segments == 4);
}

TEST_CASE("A non-finite derivative fails with the CVODE flag, the time and the component") {
  SystemBuilder system;
  system.add(std::make_unique<TestState>("test", TestState::Law::nan_after, 1.0, 0.5));
  const std::string message = failure_of(system, 2.0);
  CHECK_THAT(message,
             Catch::Matches("CVODE (failed with CV_[A-Z_]+|stalled .*) at t = 0\\.5(.|\n)*"));
  CHECK_THAT(
      message,
      Catch::Contains("the derivative of test.value (component test/test_state) is not finite"));
  CHECK_THAT(message, Catch::Contains("largest weighted local error"));
}

TEST_CASE("A solution that blows up fails naming the worst state entry") {
  SystemBuilder system;
  system.add(std::make_unique<TestState>("test", TestState::Law::blowup, 1.0));
  const std::string message = failure_of(system, 2.0);  // y = 1/(1 - t) leaves at t = 1
  CHECK_THAT(message,
             Catch::Matches("CVODE (failed with CV_[A-Z_]+|stalled .*) at t = 0\\.99(.|\n)*"));
  CHECK_THAT(message, Catch::Contains("test.value = "));
}

TEST_CASE("The same configuration and seed give bit-identical traces; another seed does not") {
  const std::string config = source_path("configs/ch7_identification.yaml");
  auto run = [&](const std::string& seed) {
    Scenario scenario = load_scenario(config, {"scenario.seed=" + seed}, shared_units());
    return simulate(scenario);
  };
  const Trace first = run("5"), second = run("5"), other = run("6");
  for (const auto& [name, values] : first.channels) {
    INFO(name);
    CHECK(values == second[name]);  // exact equality, not approximate
  }
  CHECK(first["drive/power"] != other["drive/power"]);
}

TEST_CASE("Per-state absolute tolerances from the scenario reach the solver, in the state's unit") {
  Scenario scenario =
      scenario_from_text(physical_muscle_yaml(), {"solver.atol={muscle: {temperature: 5 mK}}"});
  const auto& states = scenario.system->states();
  REQUIRE(states[0].name == "muscle.temperature");
  CHECK(scenario.solver.absolute_tolerances[0] == Approx(5e-3));
  CHECK(scenario.solver.absolute_tolerances[1] == states[1].absolute_tolerance);  // default kept
  try {
    scenario_from_text(physical_muscle_yaml(), {"solver.atol={muscle: {temprature: 5 mK}}"});
    FAIL("accepted an unknown state");
  } catch (const ConfigError& error) {
    CHECK_THAT(error.what(), Catch::Contains("solver.atol.muscle.temprature: unknown key "
                                             "'temprature' (did you mean 'temperature'?)"));
  }
}

namespace {

// Publishes how many samples it has taken; the "controller" copy reads it at the same instant.
// Its sample times are kept in its run state.
class Counter final : public SampledComponent {
 public:
  struct Run final : RunState {
    double count = 0, seen = -1;
    std::vector<double> times;
  };
  Counter(std::string group, SamplingStage stage, double period)
      : SampledComponent(std::move(group), "counter", period, stage) {}
  std::vector<OutputDeclaration> outputs() const override {
    return {{"count", "1"}, {"seen", "1"}};
  }
  std::vector<InputDeclaration> inputs() const override {
    if (sampling_stage() == SamplingStage::controller) return {{"other", false, true}};
    return {};
  }
  std::unique_ptr<RunState> create_run_state(const RunSetup&) const override {
    return std::make_unique<Run>();
  }
  void compute_outputs(const Evaluation& e) const override {
    set_output(e, 0, run_state<Run>(e).count);
    set_output(e, 1, run_state<Run>(e).seen);
  }

 protected:
  void sample(const Evaluation& e, long) const override {
    Run& run = mutable_run_state<Run>(e);
    ++run.count;
    if (sampling_stage() == SamplingStage::controller) run.seen = input(e, 0);
    run.times.push_back(e.time);
  }
};

// Records where y = -y crosses a level.
class Crossing final : public Component {
 public:
  struct Run final : RunState {
    std::vector<double> crossed_at;
  };
  explicit Crossing(double level) : Component("crossing", "crossing"), level_(level) {}
  std::vector<StateDeclaration> states() const override { return {{"value", "1", 1e-12}}; }
  std::vector<OutputDeclaration> outputs() const override { return {{"value", "1"}}; }
  std::unique_ptr<RunState> create_run_state(const RunSetup&) const override {
    return std::make_unique<Run>();
  }
  void initialize(const Evaluation&, std::span<double> own) const override { own[0] = 1.0; }
  void compute_outputs(const Evaluation& e) const override { set_output(e, 0, state(e, 0)); }
  void compute_derivatives(const Evaluation& e, double* d) const override {
    set_derivative(d, 0, -state(e, 0));
  }
  int event_count() const override { return 1; }
  int event_direction(int) const override { return -1; }
  void event_functions(const Evaluation& e, double* g) const override {
    g[0] = state(e, 0) - level_;
  }
  void at_event(int, const Evaluation& e) const override {
    mutable_run_state<Run>(e).crossed_at.push_back(e.time);
  }

 private:
  double level_;
};

}  // namespace

TEST_CASE("Sampled components act at the start and every period, estimators before controllers") {
  SystemBuilder builder;
  builder.add(std::make_unique<TestState>("plant", TestState::Law::decay, 1.0));
  auto& controller = builder.add(
      std::make_unique<Counter>("controller", Component::SamplingStage::controller, 0.05));
  const auto& estimator = builder.add(
      std::make_unique<Counter>("estimator", Component::SamplingStage::estimator, 0.05));
  builder.connect(controller, "other", "estimator.count");
  const auto system = builder.build();
  Context context(*system);
  Collector sink;
  Integrator integrator(*system, context, {});
  const auto statistics = integrator.run(0.0, 1.0, 0.5, sink);
  const auto& times = context.run_state<Counter::Run>(estimator).times;
  REQUIRE(times.size() == 20);  // 0, 0.05, ..., 0.95; the end is not a sample instant
  CHECK(times[7] == 7 * 0.05);
  CHECK(statistics.segments == 20);
  // At every instant the controller saw the estimator's count of that same instant.
  CHECK(context.signals()[static_cast<std::size_t>(system->signal_index("controller.seen"))] == 20);
}

TEST_CASE("A zero crossing is located to the solver's accuracy") {
  SystemBuilder builder;
  const auto& crossing = builder.add(std::make_unique<Crossing>(0.5));
  const auto system = builder.build();
  Context context(*system);
  Collector sink;
  SolverSettings settings;
  settings.relative_tolerance = 1e-10;
  Integrator integrator(*system, context, settings);
  const auto statistics = integrator.run(0.0, 2.0, 0.1, sink);
  const auto& crossed_at = context.run_state<Crossing::Run>(crossing).crossed_at;
  REQUIRE(crossed_at.size() == 1);  // falling only, once
  CHECK(crossed_at[0] == Approx(std::log(2.0)).epsilon(1e-8));
  CHECK(statistics.events == 1);
}

TEST_CASE("An assembly error names the origins of what caused it, the last connection first") {
  auto origins_of = [](SystemBuilder& system) {
    try {
      system.build();
    } catch (const AssemblyError& error) {
      return error.origins();
    }
    return std::vector<int>{-99};
  };
  {  // an input nothing feeds: the component's origin
    SystemBuilder system;
    system.set_origin(4);
    system.add(std::make_unique<Relay>("a", true));
    CHECK(origins_of(system) == std::vector<int>{4});
  }
  {  // a source too many: the connection that came last, then every connection's origin
    SystemBuilder system;
    system.set_origin(0);
    system.add(std::make_unique<TestState>("a", TestState::Law::decay, 1.0));
    system.add(std::make_unique<TestState>("b", TestState::Law::decay, 1.0));
    auto& relay = system.add(std::make_unique<Relay>("c", true));
    system.set_origin(1);
    system.connect(relay, "in", "a.value");
    system.set_origin(2);
    system.connect(relay, "in", "b.value");
    CHECK(origins_of(system) == std::vector<int>{2, 1, 2});
  }
  {  // a source nobody publishes: that connection's origin
    SystemBuilder system;
    auto& relay = system.add(std::make_unique<Relay>("a", true));
    system.set_origin(7);
    system.connect(relay, "in", "nowhere.value");
    CHECK(origins_of(system) == std::vector<int>{7});
  }
}
