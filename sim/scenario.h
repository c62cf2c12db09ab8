#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "sim/config/config_node.h"
#include "sim/context.h"
#include "sim/integrator.h"
#include "sim/registry.h"
#include "sim/scenario_builder.h"
#include "sim/system.h"

namespace tcpmsim {

// A scenario file turned into an assembled system, ready to integrate: each run takes a
// context of its own (make_context).
struct Scenario {
  ScenarioSettings settings;
  SolverSettings solver;
  std::shared_ptr<const System> system;
  // Parameters the command line set (--set left.mechanics.k2=3 mN/mm), in SI, applied to every
  // context make_context makes.
  std::vector<std::pair<std::string, double>> parameter_settings;
  std::string source;         // the file it came from
  std::string resolved_yaml;  // as read, with overrides and defaults
  // Values outside their typical range, located ("file:line:col: warning: key: ..."); the
  // command line prints them, and --strict makes them errors.
  std::vector<std::string> warnings;
  // The command line (or the Python call) that runs it, written into its record; empty: not
  // known (a library call).
  std::string invocation;
  // A context for one run, with the parameters as the scenario sets them.
  Context make_context() const;
};

// The sections whose keys are instances' names ("muscles", "drives"): where a --set path may
// start from an instance's name (see expand_instance_path).
std::vector<std::string> instance_sections(const KindRegistry& kinds);

// Builds a scenario from a parsed document, asking `kinds` for every section's kind; throws
// ConfigError on any bad input.
Scenario build_scenario(const ConfigNode& root, const KindRegistry& kinds);

// Reads a scenario from `text` (named `name` in messages) or a file, applying `overrides`
// ("key.path=value", the command line's --set). An override whose path names a numeric
// parameter of the model (left.mechanics.k2, or its full path muscles.left.mechanics.k2) is
// set in the run context with its unit converted here; every other override (a kind, a choice,
// a whole section) changes the document before the model is built. An override's errors are
// located at `override_origin` + "KEY=VALUE)" ("command line (--set ...)" by default).
Scenario load_scenario_text(const std::string& text, const std::string& name,
                            const std::vector<std::string>& overrides,
                            std::shared_ptr<const UnitSystem> units, const KindRegistry& kinds,
                            const std::string& override_origin = kCommandLineOrigin);
Scenario load_scenario(const std::string& file, const std::vector<std::string>& overrides,
                       std::shared_ptr<const UnitSystem> units, const KindRegistry& kinds,
                       const std::string& override_origin = kCommandLineOrigin);

}  // namespace tcpmsim
