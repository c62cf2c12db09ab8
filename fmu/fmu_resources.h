#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "sim/config/units.h"
#include "sim/scenario.h"

namespace tcpmsim::fmu {

// What an FMU carries in resources/ for its library to rebuild the model: the scenario as it
// was resolved at export (resources/scenario.yaml) and the export's choices (resources/fmu.yaml:
// model_identifier, outputs).
inline constexpr const char* kScenarioResource = "scenario.yaml";
inline constexpr const char* kSettingsResource = "fmu.yaml";

struct FmuSettings {
  std::string model_identifier;
  std::vector<std::string> outputs;  // empty: every recorded output
};

std::string settings_yaml(const FmuSettings& settings);

struct FmuResources {
  FmuSettings settings;
  Scenario scenario;
};

// Reads resources/ at `directory`. Throws std::runtime_error naming the file that is missing or
// does not load.
FmuResources read_fmu_resources(const std::string& directory,
                                std::shared_ptr<const UnitSystem> units);

// The directory a resource location names: "file:///a/b", "file:/a/b", "file://localhost/a/b"
// (percent-escapes decoded); none for another scheme.
std::optional<std::string> path_of_uri(const std::string& uri);

}  // namespace tcpmsim::fmu
