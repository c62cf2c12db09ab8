#pragma once

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "controllers/pid_controller.h"
#include "models/laws/joint.h"
#include "sim/config/config_node.h"
#include "sim/parameter_bindings.h"
#include "sim/sampled_component.h"
#include "sim/signal_reading.h"

namespace tcpmsim {

struct JointAngleSettings {
  // The angle loop, (7.7)-(7.9) with gains in W/rad on the differential power u; power_min and
  // power_max bound each muscle's power.
  PidSettings pid;
  // The controller's own model of the cables (models/laws/joint.h), for the self-sensed angle
  // (plant and model stay separate: these are not the joint's parameters).
  JointGeometry geometry;
};

namespace joint_angle {

// Push-pull around the co-contraction level c: the right muscle (which raises the angle) gets
// c + u/2, the left c - u/2, each within [P_min, P_max].
struct Powers {
  double left;
  double right;
};
inline Powers push_pull(double co_contraction, double differential, double power_min,
                        double power_max) {
  return {std::clamp(co_contraction - 0.5 * differential, power_min, power_max),
          std::clamp(co_contraction + 0.5 * differential, power_min, power_max)};
}
// The differential u beyond which neither power changes any more: |u| / 2 = the larger headroom
// of c within [P_min, P_max]. The angle loop saturates there, so its integral does not wind up.
inline double differential_limit(double co_contraction, double power_min, double power_max) {
  return 2.0 * std::max(power_max - co_contraction, co_contraction - power_min);
}

}  // namespace joint_angle

// Joint-angle control of an antagonistic pair with a co-contraction level (thesis 7.5 names the
// antagonistic set-up as the way to drive both directions by heating). Sampled with the
// drives' PWM; each sample:
//     theta[k] = the encoder's angle, or joint::angle_from_deflections of the two
//                estimators' deflections (self-sensing, from each muscle's L*)
//     u[k]     = (7.7)-(7.9) on r[k] - theta[k], saturated at +-differential_limit (7.8)
//     P_left, P_right = push_pull(c[k], u[k])
// The co-contraction c(t) (a signal in W) sets the common heating, hence the pretension, that
// keeps both muscles taut; the angle loop pushes and pulls around it. The same sample-instant
// rules as the PID hold (reference read right of a step at t_k; an angle that is not finite,
// before the estimators' first L*, holds both muscles at c without integrating).
//
// Inputs (sampled): "angle", or "left_deflection" and "right_deflection". Outputs (held):
// "left_power_command", "right_power_command", "reference", "angle" (the angle it controlled),
// "differential_demand" u before saturation, "co_contraction".
class JointAngleController final : public SampledComponent {
 public:
  enum Input { kAngle, kLeftDeflection, kRightDeflection };
  enum Output {
    kLeftPowerCommand,
    kRightPowerCommand,
    kReference,
    kAngleOutput,
    kDifferentialDemand,
    kCoContraction
  };

  JointAngleController(std::string group, JointAngleSettings settings,
                       ParameterBindings<JointAngleSettings> bindings,
                       std::unique_ptr<Signal> reference, std::unique_ptr<Signal> co_contraction,
                       double period);
  // Keys: reference (a signal in rad), co_contraction (a signal in W), gains {proportional
  // (W/rad), integral_time, derivative_time}, power_limits [P_min, P_max], anti_windup,
  // derivative_on; with self-sensing feedback also model {radius, pre_deflection {left,
  // right}}.
  static std::unique_ptr<JointAngleController> from_config(const std::string& group,
                                                           const ConfigNode& node, double period,
                                                           bool self_sensing,
                                                           const SignalContext& signals);

  std::vector<OutputDeclaration> outputs() const override;
  std::vector<InputDeclaration> inputs() const override {
    return {{"angle", false, true, InputArity::optional},
            {"left_deflection", false, true, InputArity::optional},
            {"right_deflection", false, true, InputArity::optional}};
  }
  std::string check_connections() const override;
  std::vector<ParameterDeclaration> parameters() const override;
  std::vector<SignalDeclaration> signals() const override;
  std::unique_ptr<RunState> create_run_state(const RunSetup& setup) const override;
  std::string check_parameters(const RunSetup& setup) const override;
  void compute_outputs(const Evaluation& evaluation) const override;

 protected:
  void sample(const Evaluation& evaluation, long index) const override;

 private:
  struct Run;
  double feedback_angle(const Evaluation& evaluation, const JointGeometry& geometry) const;
  JointAngleSettings defaults_;
  ParameterBindings<JointAngleSettings> bindings_;
  std::unique_ptr<Signal> reference_;
  std::unique_ptr<Signal> co_contraction_;
};

}  // namespace tcpmsim
