#pragma once

#include <memory>

#include "sim/config/config_node.h"
#include "sim/parametric_component.h"

namespace tcpmsim {

struct SensorParameters {
  double resolution = 0.0;  // quantum of the reading, in the measured unit; 0: none
};

// An instrument reading other components' outputs and publishing their sum under its own name:
// the testing machine's load cell (the forces of the muscles it holds) or position encoder.
// Optionally quantised to its resolution (thesis 7.3.1: 0.02 mm and 0.5 mN).
class Sensor final : public ParametricComponent<SensorParameters> {
 public:
  Sensor(std::string group, std::string name, std::string unit, SensorParameters defaults,
         ParameterBindings<SensorParameters> bindings);
  // The resolution from `node`'s key `resolution_key` (default 0).
  static std::unique_ptr<Sensor> from_config(const std::string& group, const std::string& name,
                                             const std::string& unit, const ConfigNode& node,
                                             const char* resolution_key);

  std::vector<OutputDeclaration> outputs() const override { return {{name_, unit_}}; }
  std::vector<InputDeclaration> inputs() const override {
    return {{"measured", true, false, InputArity::many}};
  }
  void compute_outputs(const Evaluation& evaluation) const override;

 private:
  std::string name_;
  std::string unit_;
};

}  // namespace tcpmsim
