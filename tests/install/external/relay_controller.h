// A controller kind written outside tcpmsim, against its installed headers: a relay with
// hysteresis on the self-sensed force (full power below reference - band, the lower limit above
// reference + band, the last command in between), sampled with its drive's PWM as the built-in
// PID is. Registered by name, it is used from YAML as `controller: {type: relay, ...}`.
#pragma once

#include <memory>
#include <string>

#include "sim/config/config_node.h"
#include "sim/parameter_bindings.h"
#include "sim/registry.h"
#include "sim/sampled_component.h"
#include "sim/signal.h"

namespace consumer {

struct RelaySettings {
  double band = 0.0;       // half width of the hysteresis [N]
  double power_min = 0.0;  // [W]
  double power_max = 0.0;  // [W]
};

class RelayController final : public tcpmsim::SampledComponent {
 public:
  enum Input { kEstimate };
  enum Output { kPowerCommand, kReference };

  RelayController(std::string group, double period, RelaySettings settings,
                  tcpmsim::ParameterBindings<RelaySettings> bindings,
                  std::unique_ptr<tcpmsim::Signal> reference);

  std::vector<tcpmsim::InputDeclaration> inputs() const override;
  std::vector<tcpmsim::OutputDeclaration> outputs() const override;
  std::vector<tcpmsim::ParameterDeclaration> parameters() const override;
  std::vector<tcpmsim::SignalDeclaration> signals() const override;
  std::unique_ptr<tcpmsim::RunState> create_run_state(
      const tcpmsim::RunSetup& setup) const override;
  std::string check_parameters(const tcpmsim::RunSetup& setup) const override;
  void compute_outputs(const tcpmsim::Evaluation& evaluation) const override;

 protected:
  void sample(const tcpmsim::Evaluation& evaluation, long index) const override;

 private:
  struct Run;
  RelaySettings defaults_;
  tcpmsim::ParameterBindings<RelaySettings> bindings_;
  std::unique_ptr<tcpmsim::Signal> reference_;
};

// Adds the kind "relay" to the controller category of `kinds`.
void register_relay_controller(tcpmsim::KindRegistry& kinds);

}  // namespace consumer
