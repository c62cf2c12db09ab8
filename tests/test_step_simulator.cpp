// The step-by-step simulator (sim/step_simulator.h): a controller outside the system closes the
// loop one sample at a time.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "sim/memory_run.h"
#include "sim/step_simulator.h"
#include "sim/time_grid.h"
#include "support/test_support.h"

using namespace tcpmsim;
using namespace tcpmsim::testing;

namespace {

std::string file_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// configs/ch7_control/force_steps.yaml with its PID replaced by an external controller with the
// same power limits and task (target and reference), the rest (plant, drive, estimator, seed,
// solver) as it is.
std::string external_force_steps(const std::string& duration) {
  std::string text = file_text(source_path("configs/ch7_control/force_steps.yaml"));
  const auto begin = text.find("controller:");
  const auto end = text.find("\nload:");
  const auto reference_begin = text.find("  reference:", begin);
  const std::string reference =
      text.substr(reference_begin, text.find('\n', reference_begin) + 1 - reference_begin);
  text = text.substr(0, begin) +
         "controller:\n  type: external\n  power_limits: [0.10 W, 3.12 W]\n  target: force\n" +
         reference + text.substr(end + 1);
  return replaced(text, "duration: 180 s", "duration: " + duration);
}

// The thesis' PI (7.7)-(7.9) as a researcher would write it around the simulator: explicit
// Euler integral with back-calculation, idle at P_min while the estimate is not yet defined.
struct TestPi {
  double kp, ti, period, p_min, p_max;
  double integral = 0.0;
  bool started = false;
  double command(double reference, double estimate) {
    if (!std::isfinite(estimate)) {
      started = false;
      integral = 0.0;
      return p_min;
    }
    started = true;
    const double error = reference - estimate;
    const double demand = kp * (error + integral / ti);             // (7.7)
    const double power = std::max(p_min, std::min(p_max, demand));  // (7.9)
    integral += period * (error - (demand - power) / kp);           // (7.8), explicit Euler
    return power;
  }
};

}  // namespace

TEST_CASE(
    "A PI closed around the step simulator reproduces the built-in PID's record bit for bit") {
  // Sampling and hold semantics are the PID's: the loop reads the estimate at each PWM instant
  // t_k = k T after the estimator has acted, and the power it sets is the drive's from t_k on.
  const std::string duration = "180 s";  // the whole task: 40 s lead-in, 7 steps
  const Scenario builtin = load_scenario(source_path("configs/ch7_control/force_steps.yaml"),
                                         {"scenario.duration=" + duration}, shared_units());
  const MemoryRun expected = run_in_memory(builtin);
  REQUIRE(expected.status == "complete");

  const Scenario external = scenario_from_text(external_force_steps(duration));
  StepSimulator simulator(external);
  REQUIRE(simulator.inputs().size() == 1);
  CHECK(simulator.inputs()[0].name == "controller.power_command");
  CHECK(simulator.inputs()[0].unit == "W");
  CHECK(simulator.input_range("controller.power_command") == std::pair{0.10, 3.12});

  const double period = 1.0 / 20.0;  // the PWM's
  TestPi pi{540.0, 1.0, period, 0.10, 3.12};
  long samples = 0;
  for (long k = 0; k * period <= simulator.end_time(); ++k) {
    simulator.advance_to(static_cast<double>(k) * period);
    if (simulator.finished()) break;
    // The task's reference as the external controller reports it: r(t_k), as the PID samples it.
    const double power =
        pi.command(simulator.output("controller.reference"), simulator.output("estimator.force"));
    simulator.set_input("controller.power_command", power);
    ++samples;
  }
  simulator.advance_to(simulator.end_time());
  REQUIRE(samples == 3600);
  const MemoryRun& stepped = simulator.record();
  CHECK(stepped.status == "complete");
  REQUIRE(stepped.time == expected.time);

  // Every series both records have: the plant, the drive, the estimator; the controller's
  // command and reference. The PID's own demand the external controller does not have.
  int compared = 0;
  for (std::size_t s = 0; s < stepped.series.size(); ++s) {
    const RecordSeries& series = stepped.series[s];
    const std::string channel = series.group + "/" + series.name;
    std::size_t index = 0;
    const RecordSeries* same = expected.find(channel, &index);
    if (!same) continue;
    INFO(channel);
    CHECK(bitwise_equal(stepped.values[s], expected.values[index]));
    ++compared;
  }
  CHECK(compared >= 20);
  CHECK(expected.find("controller/power_command"));
  CHECK(stepped.find("controller/reference"));
  CHECK(stepped.statistics.steps == expected.statistics.steps);
}

TEST_CASE("The step simulator refuses what a master must not do, and resets to the same run") {
  const Scenario external = scenario_from_text(external_force_steps("2 s"));
  StepSimulator simulator(external);
  CHECK(simulator.input("controller.power_command") == 0.10);  // the lower limit by default
  CHECK_THROWS_WITH(simulator.set_input("controller.power_command", 4.0),
                    Catch::Contains("controller.power_command: 4 W is outside its range [0.1, "
                                    "3.12] W"));
  CHECK_THROWS_WITH(simulator.set_input("drive.power", 1.0),
                    Catch::Contains("no external input 'drive.power'; the scenario's: "
                                    "controller.power_command"));
  CHECK_THROWS_WITH(simulator.output("muscle.nothing"), Catch::Contains("no output"));
  simulator.set_input("controller.power_command", 2.0);
  simulator.advance_to(0.5);
  CHECK_THROWS_WITH(simulator.advance_to(0.25), Catch::Contains("the run is at t = 0.5 s"));
  CHECK_THROWS_WITH(simulator.advance_to(3.0), Catch::Contains("the scenario ends at 2 s"));
  const double heated = simulator.output("muscle.temperature");
  CHECK(heated > 296.15 + 0.1);  // 2 W for half a second
  CHECK(simulator.state("muscle.thermal_force") > 0.0);
  CHECK_THROWS_WITH(simulator.state("muscle.nothing"), Catch::Contains("no state"));
  simulator.advance_to(2.0);
  CHECK(simulator.finished());
  CHECK_THROWS_WITH(simulator.set_input("controller.power_command", 1.0),
                    Catch::Contains("reached its end"));
  const std::vector<double> first = simulator.record().values.front();

  // Limits that pass one by one but not together: the reset refuses and the run is kept.
  simulator.set_parameter("controller.power_limits[0]", 3.5);
  CHECK_THROWS_WITH(simulator.reset(), Catch::Contains("power_limits"));
  CHECK(simulator.finished());
  CHECK(bitwise_equal(simulator.record().values.front(), first));
  simulator.set_parameter("controller.power_limits[0]", 0.10);

  simulator.reset();
  CHECK(simulator.time() == 0.0);
  simulator.set_input("controller.power_command", 2.0);
  simulator.advance_to(0.5);
  CHECK(simulator.output("muscle.temperature") == heated);
  simulator.advance_to(2.0);
  CHECK(bitwise_equal(simulator.record().values.front(), first));
}

TEST_CASE(
    "A stepped run on the step simulator saves the record tcpmsim run writes; one cut short says "
    "so") {
  const Scenario external = scenario_from_text(external_force_steps("1 s"));
  StepSimulator simulator(external);
  const std::string directory = process_directory("step_simulator");
  simulator.set_input("controller.power_command", 1.5);
  simulator.advance_to(0.4);
  const std::string cut = simulator.save(directory + "/cut.h5");
  CHECK(cut == directory + "/cut.interrupted.h5");
  CHECK(std::filesystem::exists(cut));
  simulator.advance_to(1.0);
  const std::string whole = simulator.save(directory + "/whole.h5");
  CHECK(whole == directory + "/whole.h5");
  CHECK(simulator.record().time.back() == 1.0);
  CHECK(simulator.record().time.size() == 21);  // 20 Hz output
}

TEST_CASE("An external controller's task is a target with its reference, each refused alone") {
  const std::string text = external_force_steps("1 s");
  auto error_of = [](const std::string& yaml) {
    try {
      scenario_from_text(yaml);
    } catch (const std::exception& error) {
      return std::string(error.what());
    }
    return std::string("no error");
  };
  CHECK_THAT(error_of(replaced(text, "  target: force\n", "")),
             Catch::Contains("controller.reference: a reference needs its target"));
  const auto reference = text.find("  reference:");
  const std::string without_reference =
      text.substr(0, reference) + text.substr(text.find('\n', reference) + 1);
  CHECK_THAT(error_of(without_reference),
             Catch::Contains("controller: a target needs the task's reference"));
  CHECK_THAT(error_of(replaced(text, "  target: force\n", "  target: deflection\n")),
             Catch::Contains("controller.reference"));  // N where a length is expected
  // With the task, the reference is an output the master reads: the lead-in at the middle of
  // the range, 0.45 N, before the first step at 40 s.
  StepSimulator simulator(scenario_from_text(text));
  CHECK(simulator.output("controller.reference") == Approx(0.45).epsilon(1e-12));
}
