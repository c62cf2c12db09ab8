#pragma once

#include <memory>
#include <string>
#include <vector>

#include "sim/config/units.h"
#include "sim/io/hdf5_writer.h"
#include "sim/scenario.h"

namespace tcpmsim {

// A scenario as a file's provenance names it: its file, resolved YAML and seed.
Provenance::Config scenario_config(const Scenario& scenario);

// The provenance of a command that read `files` with `overrides`: each loaded as a scenario (its
// resolved YAML and seed), or, if it is no scenario (a coil spring's file), its text as read.
Provenance file_provenance(const std::string& command_line, const std::vector<std::string>& files,
                           const std::vector<std::string>& overrides,
                           std::shared_ptr<const UnitSystem> units);

}  // namespace tcpmsim
