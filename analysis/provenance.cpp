#include "analysis/provenance.h"

#include <fstream>
#include <sstream>

#include "kinds/standard_kinds.h"
#include "sim/config/config_error.h"

namespace tcpmsim {

Provenance::Config scenario_config(const Scenario& scenario) {
  return {scenario.source, scenario.resolved_yaml, std::to_string(scenario.settings.seed)};
}

Provenance file_provenance(const std::string& command_line, const std::vector<std::string>& files,
                           const std::vector<std::string>& overrides,
                           std::shared_ptr<const UnitSystem> units) {
  Provenance provenance{command_line, {}};
  for (const auto& file : files) {
    try {
      provenance.configs.push_back(scenario_config(load_scenario(file, overrides, units)));
    } catch (const std::exception&) {  // no scenario: its text as read
      std::ifstream in(file);
      std::ostringstream text;
      text << in.rdbuf();
      provenance.configs.push_back({file, text.str(), ""});
    }
  }
  return provenance;
}

}  // namespace tcpmsim
