#include "kinds/standard_kinds.h"

#include "controllers/controller_kinds.h"
#include "models/model_kinds.h"
#include "signals/signal_kinds.h"

namespace tcpmsim {

KindRegistry standard_kinds() {
  KindRegistry kinds;
  register_signal_kinds(kinds);
  register_model_kinds(kinds);
  register_controller_kinds(kinds);
  return kinds;
}

Scenario load_scenario(const std::string& file, const std::vector<std::string>& overrides,
                       std::shared_ptr<const UnitSystem> units) {
  return load_scenario(file, overrides, std::move(units), standard_kinds());
}

Scenario load_scenario_text(const std::string& text, const std::string& name,
                            const std::vector<std::string>& overrides,
                            std::shared_ptr<const UnitSystem> units) {
  return load_scenario_text(text, name, overrides, std::move(units), standard_kinds());
}

Scenario build_scenario(const ConfigNode& root) {
  return build_scenario(root, standard_kinds());
}

}  // namespace tcpmsim
