#include "models/sensor.h"

#include <cmath>

namespace tcpmsim {

Sensor::Sensor(std::string group, std::string name, std::string unit, SensorParameters defaults,
               ParameterBindings<SensorParameters> bindings)
    : ParametricComponent(std::move(group), "sensor", defaults, std::move(bindings)),
      name_(std::move(name)),
      unit_(std::move(unit)) {}

std::unique_ptr<Sensor> Sensor::from_config(const std::string& group, const std::string& name,
                                            const std::string& unit, const ConfigNode& node,
                                            const char* resolution_key) {
  SensorParameters p;
  ParameterBindings<SensorParameters> bind;
  bind.quantity_or(node, resolution_key, unit, 0.0, ValueCheck::non_negative(), p,
                   bind.member(&SensorParameters::resolution));
  return std::make_unique<Sensor>(group, name, unit, p, std::move(bind));
}

void Sensor::compute_outputs(const Evaluation& evaluation) const {
  const double resolution = run_parameters(evaluation).resolution;
  const double value = input_sum(evaluation, 0);
  set_output(evaluation, 0, resolution > 0.0 ? resolution * std::round(value / resolution) : value);
}

}  // namespace tcpmsim
