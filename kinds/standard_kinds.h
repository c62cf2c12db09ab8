#pragma once

#include <memory>
#include <string>
#include <vector>

#include "sim/config/units.h"
#include "sim/registry.h"
#include "sim/scenario.h"

namespace tcpmsim {

// Every kind tcpmsim ships: the signals (signals/), the models (models/: springs, muscles,
// their thermal forms and effects, loads) and the drives, estimators and controllers
// (controllers/). The one place that knows all three layers.
KindRegistry standard_kinds();

// load_scenario and build_scenario with the standard kinds.
Scenario load_scenario(const std::string& file, const std::vector<std::string>& overrides,
                       std::shared_ptr<const UnitSystem> units);
Scenario load_scenario_text(const std::string& text, const std::string& name,
                            const std::vector<std::string>& overrides,
                            std::shared_ptr<const UnitSystem> units);
Scenario build_scenario(const ConfigNode& root);

}  // namespace tcpmsim
