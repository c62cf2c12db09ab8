#pragma once

#include <functional>
#include <memory>

#include "sim/config/config_node.h"
#include "sim/parametric_component.h"
#include "sim/signal.h"
#include "sim/signal_reading.h"

namespace tcpmsim {

// A revolute joint driven by an antagonistic pair of muscles over a pulley of radius r (thesis
// ch. 5 and section 7.5 name such set-ups as the way to drive a joint both ways by heating).
// Each muscle pulls through a cable wound on the pulley: the left one lengthens as the angle
// grows, the right one shortens,
//     x_left = x0_left + r theta,     x_right = x0_right - r theta,
// where x0 are the pre-deflections (pre-strain) at theta = 0. A cable cannot push, so a muscle
// the joint would compress goes slack (SlsMechanics' cable input). The joint's motion:
//     J dw/dt = r (F_right - F_left) - b w - k_s (theta - theta_s) + tau(t),   dtheta/dt = w,
// with inertia J, viscous damping b, an optional external spring k_s about theta_s and an
// optional load torque tau(t).
//
// Linearised about a rest where both muscles are taut, the joint's static stiffness is
//     K = -d(torque)/d(theta) = r^2 (k_left + k_right) + k_s,
// with k each muscle's relaxed stiffness dF/dx (k1 plus any attached rest stiffness): for linear
// muscles it does not depend on the pretension. JointStiffness (below) reports it as it is.
struct AntagonisticJointParameters {
  double radius = 0.0;                // r [m]
  double inertia = 0.0;               // J [kg m^2]
  double damping = 0.0;               // b [N m s/rad]
  double spring_stiffness = 0.0;      // k_s [N m/rad]
  double spring_rest_angle = 0.0;     // theta_s [rad]
  double left_pre_deflection = 0.0;   // x0_left [m]
  double right_pre_deflection = 0.0;  // x0_right [m]
  double initial_angle = 0.0;         // [rad]
  double initial_velocity = 0.0;      // [rad/s]
};

namespace joint {
// The cables' deflections at angle theta.
inline double left_deflection(const AntagonisticJointParameters& p, double angle) {
  return p.left_pre_deflection + p.radius * angle;
}
inline double right_deflection(const AntagonisticJointParameters& p, double angle) {
  return p.right_pre_deflection - p.radius * angle;
}
// The torque on the joint without inertia and damping.
inline double static_torque(const AntagonisticJointParameters& p, double angle, double left_force,
                            double right_force, double load_torque) {
  return p.radius * (right_force - left_force) -
         p.spring_stiffness * (angle - p.spring_rest_angle) + load_torque;
}
// The angle at which static_torque vanishes, the muscles' forces given as functions of their
// cables' deflections (each non-decreasing: a taut muscle's relaxed force, 0 when slack). NaN
// if the torque keeps one sign over +-1e3 rad (no balance: a load torque nothing holds).
double balance_angle(const AntagonisticJointParameters& p, double load_torque,
                     const std::function<double(double)>& left_force,
                     const std::function<double(double)>& right_force);
}  // namespace joint

class AntagonisticJoint final : public ParametricComponent<AntagonisticJointParameters> {
 public:
  enum Input { kLeftForce, kRightForce };
  enum Output {
    kAngle,
    kAngularVelocity,
    kLeftDeflection,
    kRightDeflection,
    kRadius,
    kSpringStiffness
  };
  AntagonisticJoint(std::string group, AntagonisticJointParameters defaults,
                    ParameterBindings<AntagonisticJointParameters> bindings,
                    std::unique_ptr<Signal> load_torque);
  // Keys radius, inertia, damping (0), spring {stiffness, rest_angle (0)} (none), pre_deflection
  // {left, right}, load_torque (a signal in N m; none), initial_angle (0, or `equilibrium`: then
  // `equilibrium` gives it from the parameters as read and *equilibrium_from_config is set),
  // initial_velocity (0).
  static std::unique_ptr<AntagonisticJoint> from_config(
      const std::string& group, const ConfigNode& node, const SignalContext& signals,
      const std::function<double(const AntagonisticJointParameters&, double load_torque)>&
          equilibrium,
      bool* equilibrium_from_config);

  std::vector<StateDeclaration> states() const override {
    return {{"angle", "rad", 1e-9}, {"angular_velocity", "rad/s", 1e-7}};
  }
  std::vector<OutputDeclaration> outputs() const override;
  std::vector<InputDeclaration> inputs() const override {
    return {{"left_force", false}, {"right_force", false}};
  }
  std::vector<SignalDeclaration> signals() const override;
  void initialize(const Evaluation& evaluation, std::span<double> own_state) const override;
  void compute_outputs(const Evaluation& evaluation) const override;
  void compute_derivatives(const Evaluation& evaluation, double* derivatives) const override;
  double next_breakpoint_after(const Evaluation& evaluation) const override;

  bool has_load_torque() const { return load_torque_ != nullptr; }

 private:
  double load_torque(const Evaluation& evaluation) const;
  std::unique_ptr<Signal> load_torque_;  // null: none
};

// The small-signal stiffness of an antagonistic joint, K = r^2 (k_left + k_right) + k_s, from
// what its muscles present (0 when slack): "stiffness" with their dashpots relaxed (the static
// stiffness a slow disturbance meets) and "instantaneous_stiffness" at their present state (what
// a torque step meets first). A probe of its own because it reads the muscles' outputs, which
// follow from the joint's.
class JointStiffness final : public Component {
 public:
  enum Input {
    kRadius,
    kSpringStiffness,
    kLeftStiffness,
    kRightStiffness,
    kLeftRestStiffness,
    kRightRestStiffness
  };
  enum Output { kStiffness, kInstantaneousStiffness };
  explicit JointStiffness(std::string group);
  std::vector<OutputDeclaration> outputs() const override {
    return {{"stiffness", "N*m/rad"}, {"instantaneous_stiffness", "N*m/rad"}};
  }
  std::vector<InputDeclaration> inputs() const override {
    return {
        {"radius", true},          {"spring_stiffness", true},    {"left_stiffness", true},
        {"right_stiffness", true}, {"left_rest_stiffness", true}, {"right_rest_stiffness", true}};
  }
  void compute_outputs(const Evaluation& evaluation) const override;
};

}  // namespace tcpmsim
