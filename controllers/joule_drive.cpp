#include "controllers/joule_drive.h"

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
}  // namespace

JouleDrive::JouleDrive(std::string group, JouleDriveParameters parameters,
                       std::unique_ptr<Signal> command)
    : Component(std::move(group), "joule_drive"),
      parameters_(parameters),
      command_(std::move(command)) {}

std::unique_ptr<JouleDrive> JouleDrive::from_config(const std::string& group,
                                                    const ConfigNode& node,
                                                    const SignalContext& signals) {
  using Mode = JouleDriveParameters::Mode;
  node.declare(
      {"model", "mode", "supply_voltage", "series_resistance", "power", "duty", "current"});
  JouleDriveParameters p;
  const std::string mode = node.choice("mode", {"power", "duty", "current"});
  p.mode = mode == "duty" ? Mode::duty : mode == "current" ? Mode::current : Mode::power;
  if (p.mode == Mode::duty) {
    p.supply_voltage = node.quantity("supply_voltage", "V", ValueCheck::positive());
    p.series_resistance = node.quantity("series_resistance", "ohm", ValueCheck::non_negative());
  }
  const ConfigNode command_node = node.at(command_of(p.mode).name);
  auto command = read_signal(command_node, command_of(p.mode).unit, signals);
  const auto [low, high] = command->range(0.0, signals.duration);
  if (low < 0.0) {
    command_node.fail(std::string("the ") + command_of(p.mode).name + " signal goes negative (" +
                      std::to_string(low) + ")");
  }
  if (p.mode == Mode::duty && high > 1.0) {
    command_node.fail("the duty cycle reaches " + std::to_string(high) +
                      "; it must stay in [0, 1]");
  }
  return std::make_unique<JouleDrive>(group, p, std::move(command));
}

std::vector<OutputDeclaration> JouleDrive::outputs() const {
  switch (parameters_.mode) {
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

double JouleDrive::power_from_duty(double duty, double heater_resistance) const {
  return supply().power(duty, heater_resistance);  // (7.2)
}

PwmSupply JouleDrive::supply() const {
  return {parameters_.supply_voltage, parameters_.series_resistance};
}

void JouleDrive::compute_outputs(const Evaluation& evaluation) const {
  const double command = command_->value(evaluation.signal_time);
  switch (parameters_.mode) {
    case JouleDriveParameters::Mode::power:
      set_output(evaluation, kPower, command);
      return;
    case JouleDriveParameters::Mode::duty: {
      const double heater = input(evaluation, kHeaterResistance);
      set_output(evaluation, kPower, power_from_duty(command, heater));
      set_output(evaluation, kCommand, command);
      set_output(evaluation, kCurrent, command * supply().on_current(heater));
      return;
    }
    case JouleDriveParameters::Mode::current:
      set_output(evaluation, kPower, command * command * input(evaluation, kHeaterResistance));
      set_output(evaluation, 1, command);
      return;
  }
}

double JouleDrive::next_breakpoint_after(double t) const {
  return command_->next_breakpoint_after(t);
}

std::vector<Component::SignalRecord> JouleDrive::signal_records() const {
  return {{command_of(parameters_.mode).name, command_of(parameters_.mode).unit, command_.get()}};
}

}  // namespace tcpmsim
