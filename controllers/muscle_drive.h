#pragma once

#include <memory>

#include "models/laws/pwm_supply.h"
#include "sim/component.h"
#include "sim/parameter_bindings.h"
#include "sim/random_stream.h"
#include "sim/signal_reading.h"

namespace tcpmsim {

// The Muscle Drive of thesis section 7.2.1: it heats the muscle with a PWM voltage and measures
// a proxy of the coil's inductance, L* (the "decay time"), from the current's decay in each
// off-phase.
//
// Each period T = 1/f_pwm starts with the supply on for a fraction of the period, then off:
//   on:   L(x,T) di/dt = U_b - (R_s + R_m) i
//   off:  L(x,T) di/dt = -(R_m + R_p) i        (decay through the heater and measurement path)
// and the heater dissipates R_m i^2. L* is the time from switch-off until i falls to the
// threshold i_th, t_d = L/(R_m + R_p) ln(i_0/i_th), located as a zero crossing of the simulated
// current, then quantised by the timer, with Gaussian timing noise and occasional spikes (the
// hardware's artefacts, section 7.3.1).
//
// The power law. (7.2), P = D^2 R_m (U_b/R_b)^2, and the thesis' limits (D = 0.85 gives
// 3.12 W) are quadratic in the duty parameter D, while a plain PWM dissipates in proportion to
// its on-time. The drive therefore switches on for a fraction D^2 = P / P_full of each period,
// the only timing consistent with (7.2), and reports D = sqrt(P / P_full).
//
// Fidelity `averaged` replaces the current by its period average (P by the law above) and
// computes t_d from L and R at each period's start; `switched` integrates the current (time
// constant ~0.1 us against a 50 ms period), stopping at every switching edge.
//
// The power asked for comes from a signal ("power"), or, without one, from a controller through
// the input "power_command".
struct MuscleDriveParameters {
  enum class Fidelity { averaged, switched };
  Fidelity fidelity = Fidelity::averaged;
  double pwm_frequency = 20.0;       // [Hz]
  double supply_voltage = 7.0;       // U_b [V]
  double series_resistance = 0.57;   // R_s = R_b - R_m [ohm]
  double path_resistance = 0.0;      // R_p, extra resistance of the off-phase path [ohm]
  double threshold_current = 0.014;  // i_th [A]
  double timer_resolution = 0.0;     // quantum of the decay time [s]; 0: none
  double timing_noise = 0.0;         // standard deviation of the decay time [s]
  double spike_probability = 0.0;    // per measurement
  double spike_size = 0.0;           // added to the decay time, with random sign [s]
  std::uint64_t seed = 0;            // of the measurement artefacts' random stream
  std::string stream = "muscle_drive.measurement";  // that stream's purpose
};

class MuscleDrive final : public Component {
 public:
  enum Input { kHeaterResistance, kInductance, kCommand };
  enum Output { kPower, kDuty, kCurrent, kMeasure, kOn, kDemand };

  // With `power_demand` the drive follows that signal [W]; without, it takes a "power_command"
  // input from a controller.
  MuscleDrive(std::string group, MuscleDriveParameters defaults,
              ParameterBindings<MuscleDriveParameters> bindings,
              std::unique_ptr<Signal> power_demand, double demand_duration);
  // Without a `power` key the drive takes its power from a controller.
  static std::unique_ptr<MuscleDrive> from_config(const std::string& group, const ConfigNode& node,
                                                  const SignalContext& signals);

  std::vector<StateDeclaration> states() const override;
  std::vector<OutputDeclaration> outputs() const override;
  std::vector<InputDeclaration> inputs() const override;
  std::vector<ParameterDeclaration> parameters() const override;
  std::vector<SignalDeclaration> signals() const override;
  std::unique_ptr<RunState> create_run_state(const RunSetup& setup) const override;
  std::string check_parameters(const RunSetup& setup) const override;
  void initialize(const Evaluation& evaluation, std::span<double> own_state) const override;
  void compute_outputs(const Evaluation& evaluation) const override;
  void compute_derivatives(const Evaluation& evaluation, double* derivatives) const override;
  double next_breakpoint_after(const Evaluation& evaluation) const override;
  void at_breakpoint(const Evaluation& evaluation) const override;
  void sense(const Evaluation& evaluation) const override;
  SamplingStage sampling_stage() const override { return SamplingStage::actuator; }
  bool acts_discretely() const override { return true; }
  int event_count() const override;
  int event_direction(int) const override { return -1; }
  void event_functions(const Evaluation& evaluation, double* values) const override;
  void at_event(int index, const Evaluation& evaluation) const override;
  void adapt_tolerances(const Evaluation& evaluation, std::span<double> absolute,
                        std::span<double> relative) const override;

  const MuscleDriveParameters& defaults() const { return defaults_; }

 private:
  struct Run;
  MuscleDriveParameters defaults_;
  ParameterBindings<MuscleDriveParameters> bindings_;
  std::unique_ptr<Signal> power_demand_;
  double demand_duration_;
};

}  // namespace tcpmsim
