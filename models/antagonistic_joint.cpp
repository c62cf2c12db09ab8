#include "models/antagonistic_joint.h"
#include "models/typical_values.h"

#include <cmath>
#include <limits>

namespace tcpmsim {

namespace joint {

double balance_angle(const AntagonisticJointParameters& p, double load_torque,
                     const std::function<double(double)>& left_force,
                     const std::function<double(double)>& right_force) {
  const auto torque = [&](double angle) {
    return static_torque(p, angle, left_force(left_deflection(p.geometry, angle)),
                         right_force(right_deflection(p.geometry, angle)), load_torque);
  };
  // The torque does not rise with the angle; bracket its zero, then bisect.
  double low = -1.0, high = 1.0;
  while (torque(low) < 0.0 && low > -1e3) low *= 2.0;
  while (torque(high) > 0.0 && high < 1e3) high *= 2.0;
  if (torque(low) < 0.0 || torque(high) > 0.0) return std::numeric_limits<double>::quiet_NaN();
  for (int i = 0; i < 200 && high - low > 1e-15 * (1.0 + std::abs(low)); ++i) {
    const double middle = 0.5 * (low + high);
    (torque(middle) > 0.0 ? low : high) = middle;
  }
  return 0.5 * (low + high);
}

}  // namespace joint

AntagonisticJoint::AntagonisticJoint(std::string group, AntagonisticJointParameters defaults,
                                     ParameterBindings<AntagonisticJointParameters> bindings,
                                     std::unique_ptr<Signal> load_torque)
    : ParametricComponent(std::move(group), "antagonistic_joint", defaults, std::move(bindings)),
      load_torque_(std::move(load_torque)) {}

std::unique_ptr<AntagonisticJoint> AntagonisticJoint::from_config(
    const std::string& group, const ConfigNode& node, const SignalContext& signals,
    const std::function<double(const AntagonisticJointParameters&, double)>& equilibrium) {
  using P = AntagonisticJointParameters;
  P p;
  ParameterBindings<P> bind;
  bind.quantity(node, "radius", "m", typical::joint_radius(ValueCheck::positive()), p,
                [](P& v) -> double& { return v.geometry.radius; });
  bind.quantity(node, "inertia", "kg*m^2", typical::inertia(ValueCheck::positive()), p,
                bind.member(&P::inertia));
  bind.quantity_or(node, "damping", "N*m*s/rad", 0.0, ValueCheck::non_negative(), p,
                   bind.member(&P::damping));
  if (const auto spring = node.find("spring")) {
    spring->declare({"stiffness", "rest_angle"});
    bind.quantity(*spring, "stiffness", "N*m/rad", ValueCheck::non_negative(), p,
                  bind.member(&P::spring_stiffness));
    bind.quantity_or(*spring, "rest_angle", "rad", 0.0, {}, p, bind.member(&P::spring_rest_angle));
  }
  const ConfigNode pre = node.at("pre_deflection");
  pre.declare({"left", "right"});
  bind.quantity(pre, "left", "m", {}, p,
                [](P& v) -> double& { return v.geometry.left_pre_deflection; });
  bind.quantity(pre, "right", "m", {}, p,
                [](P& v) -> double& { return v.geometry.right_pre_deflection; });
  std::unique_ptr<Signal> torque;
  if (const auto load = node.find("load_torque")) torque = read_signal(*load, "N*m", signals);
  bind.quantity_or(node, "initial_velocity", "rad/s", 0.0, {}, p,
                   bind.member(&P::initial_velocity));
  if (const auto initial = node.find("initial_angle")) {
    if (initial->is_word("equilibrium")) {
      p.initial_angle = equilibrium(p, torque ? torque->value(0.0) : 0.0);
      if (!std::isfinite(p.initial_angle)) {
        initial->fail(
            "no static balance: the torque keeps one sign over +-1000 rad (slack muscles, no "
            "spring, and a load torque?)");
      }
      bind.bind(initial->parameter_path(), "rad", {}, bind.member(&P::initial_angle));
    } else {
      bind.as_quantity(*initial, "rad", {}, p, bind.member(&P::initial_angle));
    }
  } else {
    bind.quantity_or(node, "initial_angle", "rad", 0.0, {}, p, bind.member(&P::initial_angle));
  }
  node.describe_key("initial_angle", "quantity in rad (default 0 rad), or equilibrium");
  return std::make_unique<AntagonisticJoint>(group, p, std::move(bind), std::move(torque));
}

std::vector<OutputDeclaration> AntagonisticJoint::outputs() const {
  return {{"angle", "rad"},
          {"angular_velocity", "rad/s"},
          {"left_deflection", "m"},
          {"right_deflection", "m"},
          {"stiffness", "N*m/rad", true},
          {"instantaneous_stiffness", "N*m/rad", true}};
}

std::vector<SignalDeclaration> AntagonisticJoint::signals() const {
  if (!load_torque_) return {};
  return {{"load_torque", "N*m", load_torque_.get()}};
}

double AntagonisticJoint::load_torque(const Evaluation& evaluation) const {
  return load_torque_ ? signal(evaluation, 0).value(evaluation.signal_time) : 0.0;
}

double AntagonisticJoint::load_torque_at_start(const Context& context) const {
  return load_torque_ ? signal(context, 0).value(0.0) : 0.0;
}

void AntagonisticJoint::initialize(const Evaluation& evaluation,
                                   std::span<double> own_state) const {
  const auto& p = run_parameters(evaluation);
  own_state[0] = p.initial_angle;
  own_state[1] = p.initial_velocity;
}

void AntagonisticJoint::compute_outputs(const Evaluation& evaluation) const {
  const auto& p = run_parameters(evaluation);
  const double angle = state(evaluation, 0);
  set_output(evaluation, kAngle, angle);
  set_output(evaluation, kAngularVelocity, state(evaluation, 1));
  set_output(evaluation, kLeftDeflection, joint::left_deflection(p.geometry, angle));
  set_output(evaluation, kRightDeflection, joint::right_deflection(p.geometry, angle));
}

void AntagonisticJoint::compute_observations(const Evaluation& evaluation) const {
  const auto& p = run_parameters(evaluation);
  set_output(evaluation, kStiffness,
             joint::stiffness(p.geometry, input(evaluation, kLeftRestStiffness),
                              input(evaluation, kRightRestStiffness), p.spring_stiffness));
  set_output(evaluation, kInstantaneousStiffness,
             joint::stiffness(p.geometry, input(evaluation, kLeftStiffness),
                              input(evaluation, kRightStiffness), p.spring_stiffness));
}

void AntagonisticJoint::compute_derivatives(const Evaluation& evaluation,
                                            double* derivatives) const {
  const auto& p = run_parameters(evaluation);
  const double velocity = state(evaluation, 1);
  const double torque =
      joint::static_torque(p, state(evaluation, 0), input(evaluation, kLeftForce),
                           input(evaluation, kRightForce), load_torque(evaluation));
  set_derivative(derivatives, 0, velocity);
  set_derivative(derivatives, 1, (torque - p.damping * velocity) / p.inertia);
}

double AntagonisticJoint::next_breakpoint_after(const Evaluation& evaluation) const {
  return load_torque_ ? signal(evaluation, 0).next_breakpoint_after(evaluation.time)
                      : kNoBreakpoint;
}

}  // namespace tcpmsim
