#pragma once

#include <memory>
#include <string>
#include <vector>

#include "fmu/fmu_interface.h"
#include "sim/config/units.h"

namespace tcpmsim::fmu {

struct FmuExportRequest {
  std::string scenario_file;
  std::vector<std::string> overrides;  // --set key.path=value
  std::vector<std::string> outputs;    // "muscle.force"; empty: every recorded output
  std::string output;                  // the .fmu to write
  std::string library;                 // the FMU library (tcpmsim_fmu.so) to pack
  std::string tool;                    // generationTool
};

// Writes an FMI 2.0 co-simulation FMU of the scenario: a zip with modelDescription.xml,
// binaries/linux64/<model identifier>.so (the library) and resources/ (the resolved scenario and
// the export's choices, fmu/fmu_resources.h). The interface is worked out from the resources as
// the library will work it out when instantiated, and the description is checked against the
// standard's rules before anything is written; the file appears whole or not at all. Throws
// std::runtime_error (or ConfigError, UnitError for the scenario) saying what was wrong.
FmuInterface export_fmu(const FmuExportRequest& request, std::shared_ptr<const UnitSystem> units);

}  // namespace tcpmsim::fmu
