#pragma once

#include <memory>
#include <string>
#include <vector>

#include "controllers/pid_controller.h"
#include "sim/registry.h"

namespace tcpmsim {

// Active cooling of a bundle (thesis ch. 8 names forced convection as the way to bandwidth):
// a sampled PI(D) law (7.7)-(7.9) from the members' temperatures to the fan's speed,
//     e[k] = T_measured[k] - T_ref[k],   s[k] = clamp(K (e + T_d de/dt + I / T_i), 0, 1),
// with the back-calculation (7.8) against the fan's limits 0 (off) and 1 (full). The gain is
// in 1/K and positive: the hotter, the more fan. The measure is the hottest member (keeps every
// muscle below the reference) or the members' mean.
//
// Input "temperatures" (sampled, fan-in over the members). Outputs (held): "fan_speed",
// "measured_temperature" and "reference".
class FanController final : public SampledComponent {
 public:
  enum class Measure { hottest, mean };
  enum Input { kTemperatures };
  enum Output { kFanSpeed, kMeasuredTemperature, kReference };

  FanController(std::string group, Measure measure, PidSettings settings,
                ParameterBindings<PidSettings> bindings, std::unique_ptr<Signal> reference,
                double period);
  // Keys: measure (hottest | mean), reference (a temperature signal), gains {proportional (1/K),
  // integral_time, derivative_time}, sample_period (default 0.1 s), and optional anti_windup,
  // derivative_on.
  static std::unique_ptr<FanController> from_config(const std::string& group,
                                                    const ConfigNode& node,
                                                    const SignalContext& signals);

  std::vector<OutputDeclaration> outputs() const override;
  std::vector<InputDeclaration> inputs() const override;
  std::vector<ParameterDeclaration> parameters() const override;
  std::vector<SignalDeclaration> signals() const override;
  std::unique_ptr<RunState> create_run_state(const RunSetup& setup) const override;
  std::string check_parameters(const RunSetup& setup) const override;
  void compute_outputs(const Evaluation& evaluation) const override;

 protected:
  void sample(const Evaluation& evaluation, long index) const override;

 private:
  struct Run;
  double measured(const Evaluation& evaluation) const;
  Measure measure_;
  PidSettings defaults_;
  ParameterBindings<PidSettings> bindings_;
  std::unique_ptr<Signal> reference_;
};

// Registers the controller kind "fan": a bundle's fan (thermal.fan.speed: controller) from
// its members' temperatures.
void register_fan_controller(KindRegistry& kinds);

}  // namespace tcpmsim
