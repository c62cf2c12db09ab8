#pragma once

#include <memory>
#include <string>
#include <vector>

#include "sim/component.h"
#include "sim/config/config_node.h"
#include "sim/parameter_bindings.h"

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
class ExternalController final : public Component {
 public:
  enum Output { kPowerCommand };

  ExternalController(std::string group, ExternalControllerSettings settings,
                     ParameterBindings<ExternalControllerSettings> bindings);
  static std::unique_ptr<ExternalController> from_config(const std::string& group,
                                                         const ConfigNode& node);

  std::vector<OutputDeclaration> outputs() const override;
  std::vector<ParameterDeclaration> parameters() const override;
  std::unique_ptr<RunState> create_run_state(const RunSetup& setup) const override;
  std::string check_parameters(const RunSetup& setup) const override;
  void compute_outputs(const Evaluation& evaluation) const override;
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
};

}  // namespace tcpmsim
