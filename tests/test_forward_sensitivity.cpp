// Forward sensitivities (CVODES) of a run to its parameters: against the analytic derivative of
// the thermal step response, and what they refuse.
#include <catch2/catch.hpp>

#include <cmath>

#include "sim/forward_sensitivity.h"
#include "sim/scenario.h"
#include "tests/support/test_support.h"

using namespace tcpmsim;
using namespace tcpmsim::testing;

namespace {

constexpr double kCapacity = 0.5, kConductance = 0.05, kPower = 1.5;
constexpr double kStepTime = 10.0;

// T(t) = T_amb + P/G (1 - exp(-G tau / C)), tau = t - t_step, and its derivatives by G and C.
double dT_dconductance(double t) {
  if (t < kStepTime) return 0.0;
  const double tau = t - kStepTime, decay = std::exp(-kConductance * tau / kCapacity);
  return -kPower / (kConductance * kConductance) * (1.0 - decay) +
         kPower / kConductance * decay * tau / kCapacity;
}
double dT_dcapacity(double t) {
  if (t < kStepTime) return 0.0;
  const double tau = t - kStepTime;
  return -kPower * tau * std::exp(-kConductance * tau / kCapacity) / (kCapacity * kCapacity);
}

// The outputs' sensitivities to every tracked parameter at each output time.
class SensitivityTrace final : public SensitivitySink {
 public:
  explicit SensitivityTrace(int output) : output_(static_cast<std::size_t>(output)) {}
  void record(double time, std::span<const double> signals) override {
    times.push_back(time);
    values.push_back(signals[output_]);
  }
  void record_sensitivities(double, const ForwardSensitivities& tracked) override {
    sensitivities.resize(static_cast<std::size_t>(tracked.count()));
    for (int j = 0; j < tracked.count(); ++j)
      sensitivities[static_cast<std::size_t>(j)].push_back(tracked.output_sensitivity(j)[output_]);
  }
  std::vector<double> times, values;
  std::vector<std::vector<double>> sensitivities;

 private:
  std::size_t output_;
};

const std::string kPowerStep =
    "drive.power={type: steps, initial: 0 W, times: [10 s], values: [1.5 W]}";

SensitivityTrace thermal_sensitivities(const Scenario& scenario,
                                       const std::vector<std::string>& paths) {
  Context context = scenario.make_context();
  std::vector<int> indices;
  std::vector<double> scales;
  for (const auto& path : paths) {
    indices.push_back(*scenario.system->parameter_index(path));
    scales.push_back(context.parameter(path));
  }
  ForwardSensitivities sensitivities(context, indices, scales);
  SensitivityTrace trace(scenario.system->signal_index("muscle.temperature"));
  Integrator integrator(*scenario.system, context, scenario.solver);
  integrator.run(0.0, scenario.settings.duration, {scenario.settings.output_interval},
                 sensitivities, trace);
  return trace;
}

}  // namespace

TEST_CASE(
    "The temperature's sensitivities to G and C follow the derivatives of the analytic step "
    "response") {
  // Under CVODES' error test (solver.sensitivity_error_control); a fit's default, the
  // sensitivities on the state's steps, is judged by what a fit needs of them (test_fit: central
  // differences of whole runs, and the same estimates either way).
  const Scenario scenario = scenario_from_text(
      physical_muscle_yaml(), {kPowerStep, "solver.sensitivity_error_control=true"});
  const SensitivityTrace trace = thermal_sensitivities(
      scenario, {"muscle.thermal.conductance", "muscle.thermal.heat_capacity"});
  REQUIRE(trace.sensitivities.size() == 2);
  double worst_conductance = 0.0, worst_capacity = 0.0, largest = 0.0;
  for (std::size_t i = 0; i < trace.times.size(); ++i) {
    const double t = trace.times[i];
    worst_conductance =
        std::max(worst_conductance, std::abs(trace.sensitivities[0][i] - dT_dconductance(t)));
    worst_capacity =
        std::max(worst_capacity, std::abs(trace.sensitivities[1][i] - dT_dcapacity(t)));
    largest = std::max(largest, std::abs(dT_dconductance(t)));
  }
  // dT/dG reaches P/G^2 = 600 K/(W/K); dT/dC reaches P/(e C) ~ 1.1 K/(J/K) at tau = C/G.
  // CVODES controls a sensitivity scaled by its parameter, p dT/dp (the temperature change a
  // parameter change by itself would make), like the state: its error is that of a solution at
  // this tolerance on the temperature rise P/G = 30 K.
  INFO("worst errors: dT/dG " << worst_conductance << " K/(W/K), dT/dC " << worst_capacity
                              << " K/(J/K); largest dT/dG " << largest);
  CHECK(largest > 500.0);
  const double rise = kPower / kConductance;
  CHECK(worst_conductance * kConductance <= allowed(scenario.solver.relative_tolerance, rise));
  CHECK(worst_capacity * kCapacity <= allowed(scenario.solver.relative_tolerance, rise));
}

TEST_CASE(
    "A sensitivity is zero where the parameter has not acted yet, and the state is the run's") {
  const Scenario scenario = scenario_from_text(physical_muscle_yaml(), {kPowerStep});
  const SensitivityTrace trace = thermal_sensitivities(scenario, {"muscle.thermal.conductance"});
  const Trace plain = simulate(scenario);
  // Tracking sensitivities leaves the state's own solution within the solver's tolerance.
  CHECK(max_abs_difference(trace.values, plain["muscle/temperature"]) <=
        allowed(scenario.solver.relative_tolerance, 330.0));
  for (std::size_t i = 0; i < trace.times.size() && trace.times[i] < kStepTime; ++i)
    CHECK(trace.sensitivities[0][i] == 0.0);
}

TEST_CASE("Forward sensitivities refuse what they cannot follow") {
  SECTION("a closed loop whose controller and drive act at sample instants") {
    const Scenario scenario =
        load_scenario(source_path("configs/ch7_control/deflection_steps.yaml"), {}, shared_units());
    const std::string reason = ForwardSensitivities::unsupported_reason(*scenario.system);
    CHECK_THAT(reason, Catch::Contains("changes its state at sample instants or events"));
    Context context = scenario.make_context();
    CHECK_THROWS_WITH(ForwardSensitivities(context, {0}, {1.0}),
                      Catch::StartsWith("no forward sensitivities: component"));
  }
  SECTION("a parameter that moves a discontinuity (a step's time)") {
    const Scenario scenario = scenario_from_text(physical_muscle_yaml(), {kPowerStep});
    CHECK(ForwardSensitivities::unsupported_reason(*scenario.system).empty());
    CHECK_THROWS_WITH(thermal_sensitivities(scenario, {"drive.power.times[0]"}),
                      Catch::Contains("moves the discontinuity at t = 10 s"));
  }
}
