#include "controllers/joint_angle_controller.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace tcpmsim {

// A run's angle loop and what the controller holds between samples.
struct JointAngleController::Run final : RunState {
  Run(const JointAngleSettings& values, double period)
      : settings(values), law(values.pid, period) {}
  void hold(double co_contraction) {
    command = {co_contraction, co_contraction};
    demand = 0.0;
    held_co_contraction = co_contraction;
  }
  JointAngleSettings settings;
  DiscretePid law;
  long last_index = 0;
  bool sampled = false;
  joint_angle::Powers command{0.0, 0.0};
  double demand = 0.0;
  double held_reference = std::numeric_limits<double>::quiet_NaN();
  double held_angle = std::numeric_limits<double>::quiet_NaN();
  double held_co_contraction = 0.0;
};

JointAngleController::JointAngleController(std::string group, JointAngleSettings settings,
                                           ParameterBindings<JointAngleSettings> bindings,
                                           std::unique_ptr<Signal> reference,
                                           std::unique_ptr<Signal> co_contraction, double period)
    : SampledComponent(std::move(group), "joint_angle_controller", period,
                       SamplingStage::controller),
      defaults_(settings),
      bindings_(std::move(bindings)),
      reference_(std::move(reference)),
      co_contraction_(std::move(co_contraction)) {
  DiscretePid check(defaults_.pid, period);  // throws for impossible settings
  if (!reference_ || !co_contraction_)
    throw std::invalid_argument("joint angle controller: no reference or co-contraction signal");
}

std::unique_ptr<JointAngleController> JointAngleController::from_config(
    const std::string& group, const ConfigNode& node, double period, bool self_sensing,
    const SignalContext& signals) {
  using S = JointAngleSettings;
  auto reference = read_signal(node.at("reference"), "rad", signals);
  auto co_contraction = read_signal(node.at("co_contraction"), "W", signals);
  S s;
  ParameterBindings<PidSettings> pid;
  read_pid_settings(node, "W/rad", s.pid, pid);
  ParameterBindings<S> bind;
  bind.nest<PidSettings>(pid, [](S& v) -> PidSettings& { return v.pid; });
  if (self_sensing) {
    const ConfigNode model = node.at("model");
    model.declare({"radius", "pre_deflection"});
    bind.quantity(model, "radius", "m", ValueCheck::positive(), s,
                  [](S& v) -> double& { return v.geometry.radius; });
    const ConfigNode pre = model.at("pre_deflection");
    pre.declare({"left", "right"});
    bind.quantity(pre, "left", "m", {}, s,
                  [](S& v) -> double& { return v.geometry.left_pre_deflection; });
    bind.quantity(pre, "right", "m", {}, s,
                  [](S& v) -> double& { return v.geometry.right_pre_deflection; });
  } else if (node.has("model")) {
    node.at("model").fail(
        "the encoder measures the angle: a geometry model is for "
        "feedback: self_sensing only");
  }
  return std::make_unique<JointAngleController>(group, s, std::move(bind), std::move(reference),
                                                std::move(co_contraction), period);
}

std::vector<OutputDeclaration> JointAngleController::outputs() const {
  return {{"left_power_command", "W"},  {"right_power_command", "W"},
          {"reference", "rad"},         {"angle", "rad"},
          {"differential_demand", "W"}, {"co_contraction", "W"}};
}

std::string JointAngleController::check_connections() const {
  const bool encoder = source_count(kAngle) > 0;
  const bool sensed = source_count(kLeftDeflection) > 0 && source_count(kRightDeflection) > 0;
  if (encoder == sensed) return "needs either the joint's angle or both muscles' deflections";
  return {};
}

std::vector<ParameterDeclaration> JointAngleController::parameters() const {
  return with_period(bindings_.declarations(defaults_));
}

std::vector<SignalDeclaration> JointAngleController::signals() const {
  return {{"reference", "rad", reference_.get()}, {"co_contraction", "W", co_contraction_.get()}};
}

std::unique_ptr<RunState> JointAngleController::create_run_state(const RunSetup& setup) const {
  return std::make_unique<Run>(bindings_.assign(defaults_, own_parameters(setup)),
                               setup.parameters[0]);
}

std::string JointAngleController::check_parameters(const RunSetup& setup) const {
  return pid_settings_problem(bindings_.assign(defaults_, own_parameters(setup)).pid,
                              setup.parameters[0]);
}

void JointAngleController::compute_outputs(const Evaluation& evaluation) const {
  const Run& run = run_state<Run>(evaluation);
  set_output(evaluation, kLeftPowerCommand, run.command.left);
  set_output(evaluation, kRightPowerCommand, run.command.right);
  set_output(evaluation, kReference, run.held_reference);
  set_output(evaluation, kAngleOutput, run.held_angle);
  set_output(evaluation, kDifferentialDemand, run.demand);
  set_output(evaluation, kCoContraction, run.held_co_contraction);
}

double JointAngleController::feedback_angle(const Evaluation& evaluation,
                                            const JointGeometry& geometry) const {
  if (source_count(kAngle) > 0) return input(evaluation, kAngle);
  return joint::angle_from_deflections(geometry, input(evaluation, kLeftDeflection),
                                       input(evaluation, kRightDeflection));
}

void JointAngleController::sample(const Evaluation& evaluation, long index) const {
  Run& run = mutable_run_state<Run>(evaluation);
  if (!run.sampled || index != run.last_index + 1) run.law.reset();
  run.sampled = true;
  run.last_index = index;
  const double now = evaluation.time;
  const auto& limits = run.settings.pid;
  const double level = PidController::reference_at(signal(evaluation, 1), now);
  const double co_contraction = std::clamp(level, limits.power_min, limits.power_max);
  run.hold(co_contraction);
  const Signal& reference = signal(evaluation, 0);
  run.held_reference = PidController::reference_at(reference, now);
  run.held_angle = feedback_angle(evaluation, run.settings.geometry);
  if (!std::isfinite(run.held_angle)) return;
  const double bound =
      joint_angle::differential_limit(co_contraction, limits.power_min, limits.power_max);
  const auto step =
      run.law.update(run.held_reference, PidController::reference_slope_at(reference, now),
                     run.held_angle, -bound, bound);
  run.demand = step.demand;
  run.command =
      joint_angle::push_pull(co_contraction, step.command, limits.power_min, limits.power_max);
}

}  // namespace tcpmsim
