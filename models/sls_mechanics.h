#pragma once

#include <memory>

#include "sim/component.h"
#include "sim/config/config_node.h"

namespace tcpmsim {

// The muscle's mechanics: a standard linear solid (SLS) branch in parallel with the thermal
// force and an offset,  F = F_l + F_T + phi_0   (7.5).
//
// The SLS is a spring k1 in parallel with a Maxwell arm (spring k2 in series with a dashpot
// c). Its state is the dashpot extension x_d:
//     c dx_d/dt = k2 (x - x_d),     F_l = k1 x + k2 (x - x_d).
// Differentiating F_l gives the thesis' form
//     dF_l/dt = -(k2/c) F_l + (k1 k2 / c) x + (k1 + k2) dx/dt   (7.6)
// without needing dx/dt, so a step in imposed deflection is exact (an instantaneous elastic
// response of stiffness k1 + k2). Relaxation after a deflection step has tau = c/k2; creep
// under a force step has tau = c (k1 + k2) / (k1 k2).
//
// Causality follows the load: with an imposed deflection (or a mass) x is an input and F an
// output; with an imposed force F is the input and x follows algebraically from (7.5).
struct SlsParameters {
  double k1 = 0.0;            // [N/m]
  double k2 = 0.0;            // [N/m]
  double damping = 0.0;       // c [N s/m]
  double force_offset = 0.0;  // phi_0 [N]
};

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
