#include "controllers/joule_drive.h"
#include "models/typical_values.h"

#include <cmath>

namespace tcpmsim {

namespace {
struct Command {
  const char* name;  // the config key and output channel
  const char* unit;
};

Command command_of(JouleDriveParameters::Mode mode) {
  switch (mode) {
    case JouleDriveParameters::Mode::duty:
      return {"duty", "1"};
    case JouleDriveParameters::Mode::current:
      return {"current", "A"};
    case JouleDriveParameters::Mode::power:
      break;
  }
  return {"power", "W"};
}

PwmSupply supply_of(const JouleDriveParameters& p) {
  return {p.supply_voltage, p.series_resistance};
}
}  // namespace

std::string joule_command_problem(JouleDriveParameters::Mode mode, const Signal& command,
                                  double duration) {
  const auto [low, high] = command.range(0.0, duration);
  if (low < 0.0) {
    return std::string("the ") + command_of(mode).name + " signal goes negative (" +
           std::to_string(low) + ")";
  }
  if (mode == JouleDriveParameters::Mode::duty && high > 1.0) {
    return "the duty cycle reaches " + std::to_string(high) + "; it must stay in [0, 1]";
  }
  return {};
}

JouleDrive::JouleDrive(std::string group, JouleDriveParameters defaults,
                       ParameterBindings<JouleDriveParameters> bindings,
                       std::unique_ptr<Signal> command, double command_duration)
    : ParametricComponent(std::move(group), "joule_drive", defaults, std::move(bindings)),
      command_(std::move(command)),
      command_duration_(command_duration) {}

std::unique_ptr<JouleDrive> JouleDrive::from_config(const std::string& group,
                                                    const ConfigNode& node,
                                                    const SignalContext& signals) {
  using Mode = JouleDriveParameters::Mode;
  using P = JouleDriveParameters;
  node.declare(
      {"model", "mode", "supply_voltage", "series_resistance", "power", "duty", "current"});
  P p;
  ParameterBindings<P> bind;
  const std::string mode = node.choice("mode", {"power", "duty", "current"});
  p.mode = mode == "duty" ? Mode::duty : mode == "current" ? Mode::current : Mode::power;
  if (p.mode == Mode::duty) {
    bind.quantity(node, "supply_voltage", "V", typical::supply_voltage(ValueCheck::positive()), p,
                  bind.member(&P::supply_voltage));
    bind.quantity(node, "series_resistance", "ohm", ValueCheck::non_negative(), p,
                  bind.member(&P::series_resistance));
  }
  const ConfigNode command_node = node.at(command_of(p.mode).name);
  auto command = read_signal(command_node, command_of(p.mode).unit, signals);
  if (const std::string problem = joule_command_problem(p.mode, *command, signals.duration);
      !problem.empty())
    command_node.fail(problem);
  return std::make_unique<JouleDrive>(group, p, std::move(bind), std::move(command),
                                      signals.duration);
}

std::vector<OutputDeclaration> JouleDrive::outputs() const {
  switch (defaults().mode) {
    case JouleDriveParameters::Mode::duty:
      return {{"power", "W"}, {"duty", "1"}, {"current", "A"}};
    case JouleDriveParameters::Mode::current:
      return {{"power", "W"}, {"current", "A"}};
    case JouleDriveParameters::Mode::power:
      break;
  }
  return {{"power", "W"}};
}

std::vector<InputDeclaration> JouleDrive::inputs() const {
  if (needs_resistance()) return {{"heater_resistance", true}};
  return {};
}

std::vector<SignalDeclaration> JouleDrive::signals() const {
  const Command command = command_of(defaults().mode);
  return {{command.name, command.unit, command_.get()}};
}

std::string JouleDrive::check_parameters(const RunSetup& setup) const {
  const std::string problem =
      joule_command_problem(defaults().mode, signal(setup.context, 0), command_duration_);
  return problem.empty() ? problem : std::string(command_of(defaults().mode).name) + ": " + problem;
}

void JouleDrive::compute_outputs(const Evaluation& evaluation) const {
  const auto& p = run_parameters(evaluation);
  const double command = signal(evaluation, 0).value(evaluation.signal_time);
  switch (p.mode) {
    case JouleDriveParameters::Mode::power:
      set_output(evaluation, kPower, command);
      return;
    case JouleDriveParameters::Mode::duty: {
      const double heater = input(evaluation, kHeaterResistance);
      set_output(evaluation, kPower, supply_of(p).power(command, heater));  // (7.2)
      set_output(evaluation, kCommand, command);
      set_output(evaluation, kCurrent, command * supply_of(p).on_current(heater));
      return;
    }
    case JouleDriveParameters::Mode::current:
      set_output(evaluation, kPower, command * command * input(evaluation, kHeaterResistance));
      set_output(evaluation, 1, command);
      return;
  }
}

double JouleDrive::next_breakpoint_after(const Evaluation& evaluation) const {
  return signal(evaluation, 0).next_breakpoint_after(evaluation.time);
}

}  // namespace tcpmsim
