#include "controllers/external_controller.h"

#include "sim/value_check.h"

namespace tcpmsim {

struct ExternalController::Run final : RunState {
  explicit Run(ExternalControllerSettings run_settings)
      : settings(run_settings), held(run_settings.initial_power) {}
  ExternalControllerSettings settings;
  double held;  // the power command [W]
};

ExternalController::ExternalController(std::string group, ExternalControllerSettings settings,
                                       ParameterBindings<ExternalControllerSettings> bindings)
    : Component(std::move(group), "external_controller"),
      defaults_(settings),
      bindings_(std::move(bindings)) {}

std::unique_ptr<ExternalController> ExternalController::from_config(const std::string& group,
                                                                    const ConfigNode& node) {
  using S = ExternalControllerSettings;
  node.declare({"power_limits", "initial_power"});
  S s;
  ParameterBindings<S> bind;
  bind.interval(node, "power_limits", "W", ValueCheck::non_negative(), s,
                bind.member(&S::power_min), bind.member(&S::power_max));
  bind.quantity_or(node, "initial_power", "W", s.power_min, ValueCheck::non_negative(), s,
                   bind.member(&S::initial_power));
  if (s.initial_power < s.power_min || s.initial_power > s.power_max)
    node.at("initial_power").fail("expected a power within power_limits");
  return std::make_unique<ExternalController>(group, s, std::move(bind));
}

std::vector<OutputDeclaration> ExternalController::outputs() const {
  return {{"power_command", "W"}};
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
