#pragma once

#include "sim/component.h"

namespace tcpmsim {

// An instrument reading another component's output and publishing it under its own name: the
// testing machine's load cell or position encoder. Optionally quantised to its resolution
// (thesis 7.3.1: 0.02 mm and 0.5 mN).
class Sensor final : public Component {
 public:
  Sensor(std::string group, std::string name, std::string unit, double resolution = 0.0);

  std::vector<OutputDeclaration> outputs() const override { return {{name_, unit_}}; }
  std::vector<InputDeclaration> inputs() const override { return {{"measured", true}}; }
  void compute_outputs(const Evaluation& evaluation) const override;

 private:
  std::string name_;
  std::string unit_;
  double resolution_;
};

}  // namespace tcpmsim
