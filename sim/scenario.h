#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "sim/config/config_node.h"
#include "sim/context.h"
#include "sim/integrator.h"
#include "sim/system.h"

namespace tcpmsim {

struct ScenarioSettings {
  std::string name;
  std::string description;
  double duration = 0.0;  // [s]
  std::uint64_t seed = 0;
  double output_interval = 0.0;  // [s]
  double output_start = 0.0;     // [s] first recorded time
};

// A scenario file turned into an assembled system, ready to integrate: each run takes a
// context of its own (make_context).
struct Scenario {
  ScenarioSettings settings;
  SolverSettings solver;
  std::shared_ptr<const System> system;
  std::string source;         // the file it came from
  std::string resolved_yaml;  // as read, with overrides and defaults
  // A context for one run, with the parameters as the scenario sets them.
  Context make_context() const;
};

// Builds a scenario from a parsed document; throws ConfigError on any bad input.
Scenario build_scenario(const ConfigNode& root);

// Reads a scenario file, applying `overrides` ("key.path=value").
Scenario load_scenario(const std::string& file, const std::vector<std::string>& overrides,
                       std::shared_ptr<const UnitSystem> units);

}  // namespace tcpmsim
