#pragma once

#include <memory>

#include "models/laws/pwm_supply.h"
#include "sim/parametric_component.h"
#include "sim/signal_reading.h"

namespace tcpmsim {

// Joule heating of the muscle's heater wire, averaged over the PWM period.
//
//  power:  P = P(t) prescribed.
//  duty:   P = D^2 R_m (U_b / (R_s + R_m))^2, the thesis' (7.2) with the circuit resistance
//          R_b split into the heater R_m and the rest of the circuit R_s = R_b - R_m. With a
//          constant R_m this is (7.2) exactly (U_b = 7 V, R_b = 10.75 ohm, R_m = 10.18 ohm
//          give P(D=1) = 4.31 W); with an iron heater R_m(T) the power follows the temperature.
//  current: P = I^2 R_m, I prescribed.
//
// R_m comes from the muscle's coil impedance, so there is one resistance model.
struct JouleDriveParameters {
  enum class Mode { power, duty, current };
  Mode mode = Mode::power;
  double supply_voltage = 0.0;     // U_b [V]
  double series_resistance = 0.0;  // R_s = R_b - R_m [ohm]
};

class JouleDrive final : public ParametricComponent<JouleDriveParameters> {
 public:
  enum Input { kHeaterResistance };
  enum Output { kPower, kCommand, kCurrent };

  // `command_duration`: the time over which the command is checked against its limits.
  JouleDrive(std::string group, JouleDriveParameters defaults,
             ParameterBindings<JouleDriveParameters> bindings, std::unique_ptr<Signal> command,
             double command_duration);
  static std::unique_ptr<JouleDrive> from_config(const std::string& group, const ConfigNode& node,
                                                 const SignalContext& signals);

  std::vector<OutputDeclaration> outputs() const override;
  std::vector<InputDeclaration> inputs() const override;
  std::vector<SignalDeclaration> signals() const override;
  std::string check_parameters(const RunSetup& setup) const override;
  void compute_outputs(const Evaluation& evaluation) const override;
  double next_breakpoint_after(const Evaluation& evaluation) const override;

  bool needs_resistance() const { return defaults().mode != JouleDriveParameters::Mode::power; }

 private:
  std::unique_ptr<Signal> command_;
  double command_duration_;
};

// What is wrong with a command signal over [0, duration] for `mode` (negative, or a duty above
// 1), or "".
std::string joule_command_problem(JouleDriveParameters::Mode mode, const Signal& command,
                                  double duration);

}  // namespace tcpmsim
