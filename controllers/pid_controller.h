#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "sim/config/config_node.h"
#include "sim/parameter_bindings.h"
#include "sim/sampled_component.h"
#include "sim/signal_reading.h"

namespace tcpmsim {

struct PidGains {
  double proportional = 0.0;     // K_p [W/m] or [W/N]; must not be 0 ((7.8) divides by it)
  double integral_time = 1.0;    // T_i [s]; +infinity: no integral action
  double derivative_time = 0.0;  // T_d [s]; 0: PI
};

struct PidSettings {
  PidGains gains;
  double power_min = 0.0;  // P_min [W] (7.9)
  double power_max = 0.0;  // P_max [W]
  // Back-calculation (7.8). Off, z = e: the plain integral that winds up under saturation
  // (kept for comparison).
  bool anti_windup = true;
  // What the derivative term differentiates:
  //   error:        de/dt = dr/dt - (y[k] - y[k-1]) / T, with dr/dt the reference's own right
  //                 derivative at t_k. Equals (7.7)'s de/dt for a smooth reference (a sine
  //                 sweep keeps its derivative feed-forward), but a reference step, whose
  //                 derivative is an impulse, adds nothing: no "derivative kick". With the
  //                 thesis' deflection gains a backward difference across a 3.3 mm step would
  //                 ask for |K_p| T_d 3.3 mm / T = 45 W for one sample, fourteen times P_max:
  //                 the drive saturates and (7.8) knocks the integral by T (P_d - P) / K_p.
  //   measurement:  de/dt = -(y[k] - y[k-1]) / T, the textbook set-point weight 0 (the
  //                 reference never enters the derivative).
  enum class Derivative { error, measurement };
  Derivative derivative = Derivative::error;
  // The integral's start. By default it is zero: (7.7) read literally, with the integral
  // taken from the start of control, so the first command is K_p (e + T_d de/dt); a controller
  // starting on a muscle at rest should act on the error it sees, not on a history it has not
  // had. With initial_power the start is bumpless: the integral is set at the first sample so
  // that P_d equals this power, which is what one wants when control takes over from another
  // mode at a known power (in 7.3.5 force control follows the calibration under deflection
  // control) and a jump in heating would disturb the muscle.
  std::optional<double> initial_power;
};

// The discrete law (7.7)-(7.9) on its own, one call per sample:
//     e[k]   = r[k] - y[k]
//     P_d[k] = K_p (e[k] + T_d de[k] + I[k] / T_i)                         (7.7)
//     P[k]   = max(P_min, min(P_max, P_d[k]))                              (7.9)
//     z[k]   = e[k] - (P_d[k] - P[k]) / K_p                                (7.8)
//     I[k+1] = I[k] + T z[k]                    (explicit Euler, as the thesis)
// The integral at t_k is that of z up to t_{k-1}: an implicit (backward) Euler step would put
// z[k], which depends on P[k], inside its own P_d[k] through the saturation. With T_i = inf
// there is no integral. The back-calculation (7.8) bleeds I with time constant T_i whenever
// P_d leaves [P_min, P_max]: under lasting saturation P_d settles at the limit plus K_p e (the
// proportional term alone) instead of growing with the integral of the error, and leaves the
// limit as soon as the error changes sign.
class DiscretePid {
 public:
  struct Step {
    double reference;  // r[k]
    double error;      // e[k]
    double demand;     // P_d[k]
    double command;    // P[k]
  };

  DiscretePid(PidSettings settings, double period);
  // reference_slope is dr/dt at t_k (used when derivative == error).
  Step update(double reference, double reference_slope, double estimate);
  // The same with the saturation (7.9) and the back-calculation (7.8) against limits that hold
  // for this sample only (a push-pull pair whose headroom moves with its co-contraction).
  Step update(double reference, double reference_slope, double estimate, double lower,
              double upper);
  void reset();
  bool started() const { return started_; }
  double integral() const { return integral_; }  // I[k+1] after the last update [unit of e * s]
  const PidSettings& settings() const { return settings_; }
  double period() const { return period_; }

 private:
  PidSettings settings_;
  double period_;
  bool started_ = false;
  double integral_ = 0.0;
  double previous_estimate_ = 0.0;
};

// What DiscretePid would refuse in these settings and period, or "".
std::string pid_settings_problem(const PidSettings& settings, double period);

// The keys of the discrete law: gains {proportional (in gain_unit), integral_time,
// derivative_time (optional, 0 s)}, power_limits [P_min, P_max], and optional anti_windup
// (true) and derivative_on (error | measurement; error). Shared by every controller built on
// DiscretePid.
void read_pid_settings(const ConfigNode& node, std::string_view gain_unit, PidSettings& settings,
                       ParameterBindings<PidSettings>& bindings);
// The same without power_limits, for a law whose command has fixed limits (a fan's speed).
void read_pid_gains(const ConfigNode& node, std::string_view gain_unit, PidSettings& settings,
                    ParameterBindings<PidSettings>& bindings);

// A sampled PID controller of the muscle's deflection or force through self-sensing (thesis
// 7.2.4). Input "estimate" (sampled): x^ or F^ from the estimator of the same instant. Outputs
// (held until the next sample): "power_command" P (saturated), "power_demand" P_d and
// "reference" r[k] (the reference as sampled, for step and sweep analysis).
//
// The reference is a signal the controller owns. At the sample instant t_k it is read on the
// right of any step at t_k (any step the engine treats as the same instant, within 64 ulp):
// the command computed at t_k holds over [t_k, t_{k+1}), when the new reference is in force,
// so a step on the sample grid is acted on without a period of delay.
//
// Before its first sample, and at any sample whose estimate is not finite (the estimator has
// no deflection until the Muscle Drive's first measurement), the controller holds its idle
// power (initial_power if given, else P_min) and neither integrates nor remembers the estimate;
// control starts at the first finite estimate. Each run starts afresh (its run state is
// new); within a run, a sample index that does not follow the previous one restarts it.
class PidController final : public SampledComponent {
 public:
  enum class Target { deflection, force };
  enum Input { kEstimate };
  enum Output { kPowerCommand, kPowerDemand, kReference };

  // A fixed controller (no parameters for a context to change but the sample period).
  PidController(std::string group, Target target, PidSettings settings,
                std::unique_ptr<Signal> reference, double period);
  PidController(std::string group, Target target, PidSettings settings,
                std::unique_ptr<Signal> reference, double period,
                ParameterBindings<PidSettings> bindings);
  // Keys: target (deflection | force), reference (a signal in m or N), gains {proportional
  // (W/m or W/N: "W/mm" converts), integral_time, derivative_time (optional, 0 s)},
  // power_limits [P_min, P_max], and optional anti_windup (true), derivative_on
  // (error | measurement; error), initial_power.
  static std::unique_ptr<PidController> from_config(const std::string& group,
                                                    const ConfigNode& node, double period,
                                                    const SignalContext& signals);

  std::vector<OutputDeclaration> outputs() const override;
  std::vector<InputDeclaration> inputs() const override { return {{"estimate", false, true}}; }
  std::vector<ParameterDeclaration> parameters() const override;
  std::vector<SignalDeclaration> signals() const override;
  std::unique_ptr<RunState> create_run_state(const RunSetup& setup) const override;
  std::string check_parameters(const RunSetup& setup) const override;
  void compute_outputs(const Evaluation& evaluation) const override;

  Target target() const { return target_; }
  const PidSettings& defaults() const { return defaults_; }
  // r and dr/dt as the sample at t uses them (right of a step at t), of the reference as built.
  double reference_at(double time) const { return reference_at(*reference_, time); }
  static double reference_at(const Signal& reference, double time);
  static double reference_slope_at(const Signal& reference, double time);

 protected:
  void sample(const Evaluation& evaluation, long index) const override;

 private:
  struct Run;
  Target target_;
  PidSettings defaults_;
  ParameterBindings<PidSettings> bindings_;
  std::unique_ptr<Signal> reference_;
};

}  // namespace tcpmsim
