#pragma once

#include <functional>
#include <memory>

#include "models/laws/joint.h"
#include "sim/config/config_node.h"
#include "sim/parametric_component.h"
#include "sim/signal.h"
#include "sim/signal_reading.h"

namespace tcpmsim {

// A revolute joint driven by an antagonistic pair of muscles over a pulley (thesis ch. 5 and
// section 7.5 name such set-ups as the way to drive a joint both ways by heating), the cables as
// in models/laws/joint.h. A cable cannot push, so a muscle the joint would compress goes slack
// (SlsMechanics' cable input). The joint's motion:
//     J dw/dt = r (F_right - F_left) - b w - k_s (theta - theta_s) + tau(t),   dtheta/dt = w,
// with inertia J, viscous damping b, an optional external spring k_s about theta_s and an
// optional load torque tau(t).
//
// Linearised about a rest, the joint's stiffness is joint::stiffness, r^2 (k_left + k_right) +
// k_s: for linear muscles it does not depend on the pretension. The joint records it (observed)
// from what its muscles present: "stiffness" with their dashpots relaxed (the static stiffness a
// slow disturbance meets) and "instantaneous_stiffness" at their present state (what a torque
// step meets first).
struct AntagonisticJointParameters {
  JointGeometry geometry;
  double inertia = 0.0;            // J [kg m^2]
  double damping = 0.0;            // b [N m s/rad]
  double spring_stiffness = 0.0;   // k_s [N m/rad]
  double spring_rest_angle = 0.0;  // theta_s [rad]
  double initial_angle = 0.0;      // [rad]
  double initial_velocity = 0.0;   // [rad/s]
};

namespace joint {
// The torque on the joint without inertia and damping.
inline double static_torque(const AntagonisticJointParameters& p, double angle, double left_force,
                            double right_force, double load_torque) {
  return p.geometry.radius * (right_force - left_force) -
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
  enum Input {
    kLeftForce,
    kRightForce,
    kLeftStiffness,
    kRightStiffness,
    kLeftRestStiffness,
    kRightRestStiffness
  };
  enum Output {
    kAngle,
    kAngularVelocity,
    kLeftDeflection,
    kRightDeflection,
    kStiffness,
    kInstantaneousStiffness
  };
  AntagonisticJoint(std::string group, AntagonisticJointParameters defaults,
                    ParameterBindings<AntagonisticJointParameters> bindings,
                    std::unique_ptr<Signal> load_torque);
  // Keys radius, inertia, damping (0), spring {stiffness, rest_angle (0)} (none), pre_deflection
  // {left, right}, load_torque (a signal in N m; none), initial_angle (0, or `equilibrium`: then
  // `equilibrium` gives it from the parameters as read), initial_velocity (0).
  static std::unique_ptr<AntagonisticJoint> from_config(
      const std::string& group, const ConfigNode& node, const SignalContext& signals,
      const std::function<double(const AntagonisticJointParameters&, double load_torque)>&
          equilibrium);

  std::vector<StateDeclaration> states() const override {
    return {{"angle", "rad", 1e-9}, {"angular_velocity", "rad/s", 1e-7}};
  }
  std::vector<OutputDeclaration> outputs() const override;
  // The forces drive the motion; the muscles' stiffnesses only the record.
  std::vector<InputDeclaration> inputs() const override {
    return {{"left_force", false},          {"right_force", false},
            {"left_stiffness", false},      {"right_stiffness", false},
            {"left_rest_stiffness", false}, {"right_rest_stiffness", false}};
  }
  std::vector<SignalDeclaration> signals() const override;
  void initialize(const Evaluation& evaluation, std::span<double> own_state) const override;
  void compute_outputs(const Evaluation& evaluation) const override;
  void compute_observations(const Evaluation& evaluation) const override;
  void compute_derivatives(const Evaluation& evaluation, double* derivatives) const override;
  double next_breakpoint_after(const Evaluation& evaluation) const override;

  // The load torque at t = 0 as `context` has it (0 without one).
  double load_torque_at_start(const Context& context) const;

 private:
  double load_torque(const Evaluation& evaluation) const;
  std::unique_ptr<Signal> load_torque_;  // null: none
};

}  // namespace tcpmsim
