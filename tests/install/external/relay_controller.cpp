#include "relay_controller.h"

#include <cmath>
#include <limits>

#include "controllers/controller_facts.h"
#include "sim/scenario_builder.h"
#include "sim/signal_reading.h"
#include "sim/time_grid.h"
#include "sim/value_check.h"

namespace consumer {

using namespace tcpmsim;

// What a run holds between samples: the last command and the reference it answered.
struct RelayController::Run final : RunState {
  explicit Run(RelaySettings run_settings)
      : settings(run_settings), command(run_settings.power_min) {}
  RelaySettings settings;
  double command;
  double reference = std::numeric_limits<double>::quiet_NaN();
};

RelayController::RelayController(std::string group, double period, RelaySettings settings,
                                 ParameterBindings<RelaySettings> bindings,
                                 std::unique_ptr<Signal> reference)
    : SampledComponent(std::move(group), "relay_controller", period, SamplingStage::controller),
      defaults_(settings),
      bindings_(std::move(bindings)),
      reference_(std::move(reference)) {}

std::vector<InputDeclaration> RelayController::inputs() const {
  return {{"estimate", false, true}};  // read at the sample instants only
}

std::vector<OutputDeclaration> RelayController::outputs() const {
  return {{"power_command", "W"}, {"reference", "N"}};
}

std::vector<ParameterDeclaration> RelayController::parameters() const {
  return with_period(bindings_.declarations(defaults_));
}

std::vector<SignalDeclaration> RelayController::signals() const {
  return {{"reference", "N", reference_.get()}};
}

std::unique_ptr<RunState> RelayController::create_run_state(const RunSetup& setup) const {
  return std::make_unique<Run>(bindings_.assign(defaults_, own_parameters(setup)));
}

std::string RelayController::check_parameters(const RunSetup& setup) const {
  const RelaySettings s = bindings_.assign(defaults_, own_parameters(setup));
  return s.power_min < s.power_max ? "" : "power_limits: expected the lower limit below the upper";
}

void RelayController::compute_outputs(const Evaluation& evaluation) const {
  const Run& run = run_state<Run>(evaluation);
  set_output(evaluation, kPowerCommand, run.command);
  set_output(evaluation, kReference, run.reference);
}

void RelayController::sample(const Evaluation& evaluation, long /*index*/) const {
  Run& run = mutable_run_state<Run>(evaluation);
  const double t = evaluation.time;
  run.reference = signal(evaluation, 0).value(t + time_margin(t));  // right of a step at t
  const double estimate = input(evaluation, kEstimate);
  const RelaySettings& s = run.settings;
  if (!std::isfinite(estimate))
    run.command = s.power_min;  // the estimator's filters are still filling
  else if (estimate < run.reference - s.band)
    run.command = s.power_max;
  else if (estimate > run.reference + s.band)
    run.command = s.power_min;
}

namespace {

// controller: {type: relay, reference: <signal in N>, band: <N>, power_limits: [<W>, <W>],
//              estimator: <name>}: on the estimator's force, commanding that estimator's drive.
void build_relay(const ConfigNode& node, const std::string& name, ScenarioBuilder& build) {
  node.declare({"estimator", "reference", "band", "power_limits"});
  const auto& estimator = build.linked(node, "estimator", kEstimatorCategory);
  const std::string drive = build.facts<EstimatorFacts>(estimator.name)->drive;
  const MuscleDriveFacts& facts = sensing_drive(node, drive, build);
  check_takes_command(facts);
  RelaySettings s;
  ParameterBindings<RelaySettings> bind;
  bind.quantity(node, "band", "N", ValueCheck::positive(), s, bind.member(&RelaySettings::band));
  bind.interval(node, "power_limits", "W", ValueCheck::non_negative(), s,
                bind.member(&RelaySettings::power_min), bind.member(&RelaySettings::power_max));
  auto reference = read_signal(node.at("reference"), "N", build.signals());
  SystemBuilder& system = build.system();
  auto& controller = system.add(std::make_unique<RelayController>(
      name, facts.period, s, std::move(bind), std::move(reference)));
  system.connect(controller, "estimate", estimator.name + ".force");
  system.connect(drive + ".power_command", name + ".power_command");
  follow_pwm(build, name, drive);
}

}  // namespace

void register_relay_controller(KindRegistry& kinds) {
  kinds.add({kControllerCategory,
             "relay",
             "a relay with hysteresis on the self-sensed force (a user's kind)",
             {},
             InstanceBuilder(build_relay)});
}

}  // namespace consumer
