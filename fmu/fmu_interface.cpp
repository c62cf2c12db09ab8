#include "fmu/fmu_interface.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdio>
#include <stdexcept>

#include "sim/config/config_error.h"
#include "sim/step_simulator.h"

namespace tcpmsim::fmu {
namespace {

// "b/m003/muscle" -> "b.m003.muscle": FMI's structured names separate levels by dots.
std::string structured(std::string name) {
  std::replace(name.begin(), name.end(), '/', '.');
  return name;
}

// FNV-1a over the text, twice with different offsets, as the 128 bits of a GUID: the same
// scenario and variables give the same GUID on any machine.
std::string digest_guid(const std::string& text) {
  auto fnv = [&](std::uint64_t hash) {
    for (const unsigned char c : text) hash = (hash ^ c) * 1099511628211ULL;
    return hash;
  };
  const std::uint64_t high = fnv(14695981039346656037ULL);
  const std::uint64_t low = fnv(high ^ 0x9e3779b97f4a7c15ULL);
  char text_guid[40];
  std::snprintf(text_guid, sizeof text_guid, "{%08x-%04x-%04x-%04x-%012llx}",
                static_cast<unsigned>(high >> 32), static_cast<unsigned>((high >> 16) & 0xffff),
                static_cast<unsigned>(high & 0xffff), static_cast<unsigned>(low >> 48),
                static_cast<unsigned long long>(low & 0xffffffffffffULL));
  return text_guid;
}

std::vector<FmuVariable> input_variables(const StepSimulator& simulator) {
  std::vector<FmuVariable> variables;
  for (const auto& input : simulator.inputs()) {
    FmuVariable variable;
    variable.name = structured(input.name);
    variable.target = input.name;
    variable.causality = FmuVariable::Causality::input;
    variable.unit = input.unit;
    variable.start = simulator.input(input.name);
    std::tie(variable.min, variable.max) = simulator.input_range(input.name);
    variable.has_range = true;
    variable.description = "held from the instant it is set (zero-order hold)";
    variables.push_back(variable);
  }
  return variables;
}

std::vector<FmuVariable> output_variables(const Scenario& scenario,
                                          const std::vector<std::string>& outputs) {
  std::vector<FmuVariable> variables;
  const auto& channels = scenario.system->channels();
  auto add = [&](const ChannelInfo& channel) {
    FmuVariable variable;
    variable.target = channel.group + "." + channel.name;
    variable.name = structured(variable.target);
    variable.causality = FmuVariable::Causality::output;
    variable.unit = channel.unit;
    variables.push_back(variable);
  };
  const auto& inputs = scenario.system->external_inputs();
  const auto is_input = [&](const std::string& name) {
    return std::any_of(inputs.begin(), inputs.end(),
                       [&](const ExternalInputInfo& i) { return i.name == name; });
  };
  if (outputs.empty()) {
    // Every recorded channel but the external inputs' own (an input is its own variable).
    for (const auto& channel : channels) {
      if (channel.recorded && !is_input(channel.group + "." + channel.name)) add(channel);
    }
    return variables;
  }
  for (auto output = outputs.begin(); output != outputs.end(); ++output) {
    if (std::find(outputs.begin(), output, *output) != output)
      throw UsageError("--outputs: '" + *output + "' is named twice");
    if (is_input(*output))
      throw UsageError(
          "--outputs: '" + *output +
          "' is an external input, a variable of the FMU already (its master sets it)");
  }
  for (const auto& output : outputs) {
    const auto found = std::find_if(channels.begin(), channels.end(), [&](const ChannelInfo& c) {
      return c.recorded && c.group + "." + c.name == output;
    });
    if (found == channels.end()) {
      std::string known;
      for (const auto& channel : channels)
        if (channel.recorded)
          known += (known.empty() ? "" : ", ") + channel.group + "." + channel.name;
      throw UsageError("--outputs: no recorded output '" + output + "' in '" +
                       scenario.settings.name + "'; it records: " + known);
    }
    add(*found);
  }
  return variables;
}

std::vector<FmuVariable> parameter_variables(const Scenario& scenario,
                                             const StepSimulator& simulator) {
  std::vector<FmuVariable> variables;
  for (const auto& parameter : scenario.system->parameters()) {
    if (!parameter.derived_from.empty()) continue;  // follows others; cannot be set
    FmuVariable variable;
    variable.target = parameter.declaration.path;
    // Under "parameters.": a parameter may share its path with an output (muscle.resistance,
    // the nominal value and the one the run computes).
    variable.name = "parameters." + structured(variable.target);
    variable.causality = FmuVariable::Causality::parameter;
    variable.unit = parameter.declaration.unit;
    variable.start = simulator.parameter(variable.target);
    if (!parameter.declaration.check.unbounded())
      variable.description = parameter.declaration.check.expectation();
    variables.push_back(variable);
  }
  return variables;
}

}  // namespace

const FmuVariable* FmuInterface::find(unsigned value_reference) const {
  if (value_reference >= variables.size()) return nullptr;
  return &variables[value_reference];
}

std::string model_identifier_for(const std::string& scenario_name) {
  std::string identifier;
  for (const char c : scenario_name)
    identifier += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  if (identifier.empty() || std::isdigit(static_cast<unsigned char>(identifier.front())))
    identifier = "tcpmsim_" + identifier;
  return identifier;
}

FmuInterface fmu_interface(const Scenario& scenario, const std::vector<std::string>& outputs,
                           const std::string& model_identifier) {
  const StepSimulator simulator(scenario);
  FmuInterface fmu;
  fmu.model_name = scenario.settings.name;
  fmu.model_identifier = model_identifier;
  fmu.description = "tcpmsim scenario '" + scenario.settings.name +
                    "' as a co-simulation FMU: its external inputs held between steps";
  fmu.stop_time = scenario.settings.duration;
  fmu.tolerance = scenario.solver.relative_tolerance;
  fmu.variables = input_variables(simulator);
  if (fmu.variables.empty())
    throw UsageError(
        "'" + scenario.settings.name +
        "' has no external input for an FMU's master to set (a controller section of type "
        "external)");
  for (auto& variable : output_variables(scenario, outputs)) fmu.variables.push_back(variable);
  for (auto& variable : parameter_variables(scenario, simulator)) fmu.variables.push_back(variable);
  std::string identity = scenario.resolved_yaml + "\n" + model_identifier;
  for (std::size_t k = 0; k < fmu.variables.size(); ++k) {
    fmu.variables[k].value_reference = static_cast<unsigned>(k);
    identity += "\n" + fmu.variables[k].name + " " + fmu.variables[k].unit;
  }
  fmu.guid = digest_guid(identity);
  return fmu;
}

}  // namespace tcpmsim::fmu
