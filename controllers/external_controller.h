#pragma once

#include <memory>
#include <string>
#include <vector>

#include "sim/component.h"
#include "sim/config/config_node.h"
#include "sim/parameter_bindings.h"
#include "sim/signal.h"
#include "sim/signal_reading.h"

namespace tcpmsim {

struct ExternalControllerSettings {
  double power_min = 0.0;      // [W]
  double power_max = 0.0;      // [W]
  double initial_power = 0.0;  // held until the first command [W]
};

// A controller that lives outside the system: a Python function, a Simulink or Modelica model
// through the FMU, a user's C++ loop (sim/stepper.h). It sits where the built-in PID sits (the
// controller stage, commanding a Muscle Drive's power) and holds the power its master last set,
// within power_limits; its master sets it after the instant's instruments and estimators have
// acted and before the drive latches it, so a command set at t_k is the drive's from t_k on, as
// the PID's (7.7)-(7.9) is.
//
// It may carry the task's reference (target: force | deflection, reference: a signal in N or m),
// which it only reports: output "reference" is r(t_k) as the PID samples it (right of a step at
// t_k), latched at each instant t_k and held until the next, so the master reads the task from
// the outputs and the record is the built-in controller's (a step at the run's end is never in
// force), analysed as it is (tcpmsim.control_task, tcpmsim analyze --reference).
class ExternalController final : public Component {
 public:
  enum Output { kPowerCommand, kReference };

  ExternalController(std::string group, ExternalControllerSettings settings,
                     ParameterBindings<ExternalControllerSettings> bindings,
                     std::unique_ptr<Signal> reference = nullptr, std::string reference_unit = "");
  static std::unique_ptr<ExternalController> from_config(const std::string& group,
                                                         const ConfigNode& node,
                                                         const SignalContext& signals);

  std::vector<OutputDeclaration> outputs() const override;
  std::vector<ParameterDeclaration> parameters() const override;
  std::vector<SignalDeclaration> signals() const override;
  std::unique_ptr<RunState> create_run_state(const RunSetup& setup) const override;
  std::string check_parameters(const RunSetup& setup) const override;
  void compute_outputs(const Evaluation& evaluation) const override;
  void sense(const Evaluation& evaluation) const override;
  void at_breakpoint(const Evaluation& evaluation) const override;
  SamplingStage sampling_stage() const override { return SamplingStage::controller; }
  bool acts_discretely() const override { return true; }
  std::vector<ExternalInputDeclaration> external_inputs() const override;
  std::pair<double, double> external_input_range(const Evaluation& evaluation,
                                                 int index) const override;
  void hold_external_input(const Evaluation& evaluation, int index, double value) const override;

 private:
  struct Run;
  ExternalControllerSettings defaults_;
  ParameterBindings<ExternalControllerSettings> bindings_;
  std::unique_ptr<Signal> reference_;  // null without a task
  std::string reference_unit_;
};

}  // namespace tcpmsim
