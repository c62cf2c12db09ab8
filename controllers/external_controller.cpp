#include "controllers/external_controller.h"

#include <limits>

#include "controllers/pid_controller.h"
#include "sim/value_check.h"

namespace tcpmsim {

struct ExternalController::Run final : RunState {
  explicit Run(ExternalControllerSettings run_settings)
      : settings(run_settings), held(run_settings.initial_power) {}
  ExternalControllerSettings settings;
  double held;                                                  // the power command [W]
  double reference = std::numeric_limits<double>::quiet_NaN();  // r(t_k) of the last instant
};

ExternalController::ExternalController(std::string group, ExternalControllerSettings settings,
                                       ParameterBindings<ExternalControllerSettings> bindings,
                                       std::unique_ptr<Signal> reference,
                                       std::string reference_unit)
    : Component(std::move(group), "external_controller"),
      defaults_(settings),
      bindings_(std::move(bindings)),
      reference_(std::move(reference)),
      reference_unit_(std::move(reference_unit)) {}

namespace {

// The optional task: target (force | deflection) names the reference's unit, N or m.
std::pair<std::unique_ptr<Signal>, std::string> read_reference(const ConfigNode& node,
                                                               const SignalContext& signals) {
  const auto target = node.find("target");
  const auto reference = node.find("reference");
  if (!reference && !target) return {nullptr, ""};
  if (!reference) node.fail("a target needs the task's reference (reference: a signal)");
  if (!target)
    reference->fail("a reference needs its target (target: force | deflection) for its unit");
  const std::string unit = node.choice("target", {"deflection", "force"}) == "force" ? "N" : "m";
  return {read_signal(*reference, unit, signals), unit};
}

}  // namespace

std::unique_ptr<ExternalController> ExternalController::from_config(const std::string& group,
                                                                    const ConfigNode& node,
                                                                    const SignalContext& signals) {
  using S = ExternalControllerSettings;
  node.declare({"power_limits", "initial_power", "target", "reference"});
  S s;
  ParameterBindings<S> bind;
  bind.interval(node, "power_limits", "W", ValueCheck::non_negative(), s,
                bind.member(&S::power_min), bind.member(&S::power_max));
  bind.quantity_or(node, "initial_power", "W", s.power_min, ValueCheck::non_negative(), s,
                   bind.member(&S::initial_power));
  if (s.initial_power < s.power_min || s.initial_power > s.power_max)
    node.at("initial_power").fail("expected a power within power_limits");
  auto [reference, unit] = read_reference(node, signals);
  return std::make_unique<ExternalController>(group, s, std::move(bind), std::move(reference),
                                              unit);
}

std::vector<OutputDeclaration> ExternalController::outputs() const {
  if (!reference_) return {{"power_command", "W"}};
  return {{"power_command", "W"}, {"reference", reference_unit_}};
}

std::vector<SignalDeclaration> ExternalController::signals() const {
  if (!reference_) return {};
  return {{"reference", reference_unit_, reference_.get()}};
}

std::vector<ParameterDeclaration> ExternalController::parameters() const {
  return bindings_.declarations(defaults_);
}

std::unique_ptr<RunState> ExternalController::create_run_state(const RunSetup& setup) const {
  return std::make_unique<Run>(bindings_.assign(defaults_, setup.parameters));
}

std::string ExternalController::check_parameters(const RunSetup& setup) const {
  const auto s = bindings_.assign(defaults_, setup.parameters);
  if (!(s.power_min < s.power_max)) return "power_limits: expected the lower limit below the upper";
  if (s.initial_power < s.power_min || s.initial_power > s.power_max)
    return "initial_power: expected a power within power_limits";
  return {};
}

void ExternalController::compute_outputs(const Evaluation& evaluation) const {
  set_output(evaluation, kPowerCommand, run_state<Run>(evaluation).held);
  if (reference_) set_output(evaluation, kReference, run_state<Run>(evaluation).reference);
}

// Each instant, before the master reads the outputs (sense) and once at the start of a run
// (at_breakpoint): r(t_k) as the PID samples it.
void ExternalController::sense(const Evaluation& evaluation) const {
  if (reference_)
    mutable_run_state<Run>(evaluation).reference =
        PidController::reference_at(signal(evaluation, 0), evaluation.time);
}

void ExternalController::at_breakpoint(const Evaluation& evaluation) const {
  sense(evaluation);
}

std::vector<ExternalInputDeclaration> ExternalController::external_inputs() const {
  return {{"power_command", "W"}};
}

std::pair<double, double> ExternalController::external_input_range(const Evaluation& evaluation,
                                                                   int /*index*/) const {
  const auto& settings = run_state<Run>(evaluation).settings;
  return {settings.power_min, settings.power_max};
}

void ExternalController::hold_external_input(const Evaluation& evaluation, int /*index*/,
                                             double value) const {
  mutable_run_state<Run>(evaluation).held = value;
}

}  // namespace tcpmsim
