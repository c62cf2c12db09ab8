#include "models/sensor.h"

#include <cmath>

namespace tcpmsim {

Sensor::Sensor(std::string group, std::string name, std::string unit, double resolution)
    : Component(std::move(group), "sensor"),
      name_(std::move(name)),
      unit_(std::move(unit)),
      resolution_(resolution) {}

void Sensor::compute_outputs(const Evaluation& evaluation) const {
  const double value = input(evaluation, 0);
  set_output(evaluation, 0,
             resolution_ > 0.0 ? resolution_ * std::round(value / resolution_) : value);
}

}  // namespace tcpmsim
