#pragma once

#include <memory>

#include "models/laws/sls.h"
#include "sim/component.h"
#include "sim/config/config_node.h"

namespace tcpmsim {

// The muscle's mechanics as a component: the SLS of (7.5)-(7.6) (models/laws/sls.h) with the
// dashpot extension x_d as its state.
//
// Causality follows the load: with an imposed deflection (or a mass) x is an input and F an
// output; with an imposed force F is the input and x follows algebraically from (7.5).
class SlsMechanics final : public Component {
 public:
  enum class Drive { deflection, force };
  enum Input { kThermalForce, kImposed };
  enum Output { kForce, kDeflection, kElasticForce };

  SlsMechanics(std::string group, SlsParameters parameters, Drive drive);
  static SlsParameters parameters_from_config(const ConfigNode& node);

  std::vector<StateDeclaration> states() const override {
    return {{"dashpot_extension", "m", 1e-12}};
  }
  std::vector<OutputDeclaration> outputs() const override;
  std::vector<InputDeclaration> inputs() const override;
  void initialize(const Evaluation& evaluation, std::span<double> own_state) const override;
  void compute_outputs(const Evaluation& evaluation) const override;
  void compute_derivatives(const Evaluation& evaluation, double* derivatives) const override;
  Dependencies derivative_dependencies(int state_index) const override;

  const SlsParameters& parameters() const { return parameters_; }

 private:
  double deflection(const Evaluation& evaluation) const;

  SlsParameters parameters_;
  Drive drive_;
};

}  // namespace tcpmsim
