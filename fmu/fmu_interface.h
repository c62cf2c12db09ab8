#pragma once

#include <string>
#include <vector>

#include "sim/scenario.h"

namespace tcpmsim::fmu {

// One scalar variable an FMU of a scenario exposes (FMI 2.0 section 2.2.7), all Real, in SI.
struct FmuVariable {
  enum class Causality { input, output, parameter };
  std::string name;    // FMI's structured name: "controller.power_command", "muscle.force"
  std::string target;  // what it addresses: the StepSimulator's input, output or parameter path
  Causality causality = Causality::output;
  unsigned value_reference = 0;
  std::string unit;             // SI, as the scenario states it ("N/m", "1")
  double start = 0.0;           // inputs and parameters: the value a run starts with
  double min = 0.0, max = 0.0;  // inputs: the range a master may set
  bool has_range = false;
  std::string description;
};

// What an FMU of a scenario is: its identity and its variables, worked out the same way by the
// exporter (tcpmsim export-fmu) and by the FMU's library when it is instantiated from the
// scenario it carries, so that the two agree by construction; the GUID, a digest of the
// scenario and the variables, checks that they were made from the same files.
struct FmuInterface {
  std::string model_name;        // the scenario's name
  std::string model_identifier;  // the shared library's name: binaries/linux64/<id>.so
  std::string guid;
  std::string description;
  double stop_time = 0.0;              // the scenario's duration [s]
  double tolerance = 0.0;              // the solver's relative tolerance
  std::vector<FmuVariable> variables;  // inputs, then outputs, then parameters

  const FmuVariable* find(unsigned value_reference) const;
};

// The interface of `scenario`'s FMU: its external inputs (start: the value held at t = 0, range:
// the one the run allows), the outputs named in `outputs` ("muscle.force"; empty: every scalar
// recorded channel), and every parameter that can be set (not derived ones). Throws
// std::invalid_argument for a scenario without external inputs or an output it does not record.
FmuInterface fmu_interface(const Scenario& scenario, const std::vector<std::string>& outputs,
                           const std::string& model_identifier);

// A model identifier from a scenario's name: a C identifier (letters, digits, underscores, not
// starting with a digit), as FMI asks of the library's name.
std::string model_identifier_for(const std::string& scenario_name);

}  // namespace tcpmsim::fmu
