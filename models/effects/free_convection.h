#pragma once

#include <memory>

#include "sim/config/config_node.h"
#include "sim/parametric_component.h"

namespace tcpmsim {

// Laminar free convection from the muscle, attached to its heat balance: the heat transfer
// coefficient of a body in still air grows with the temperature difference as dT^(1/4)
// (Nu ~ Ra^(1/4), the laminar range of Churchill and Chu's correlations), so the loss is
//     Q = G dT_ref (dT / dT_ref)^(5/4),   dT = T - T_amb,
// stated by its conductance G [W/K] at a reference difference dT_ref (Q = G dT there). Below
// ambient the same law cools in reverse, Q = -G dT_ref (|dT| / dT_ref)^(5/4). Beside the node's
// linear conductance it makes the steady temperature rise less than linearly with power: a
// candidate for the cooling the thesis found mismatched at low power (physics.md section 3),
// which the measured data must confirm or refute. The exponent n of (dT / dT_ref)^n may be given
// (1 to 2; 5/4 laminar by default, 4/3 turbulent): discover's convection family frees it.
struct FreeConvectionParameters {
  double conductance = 0.0;           // G [W/K] at the reference difference
  double reference_difference = 0.0;  // dT_ref [K]
  double exponent = 0.0;              // n; 0: the laminar 5/4
};

class FreeConvection final : public ParametricComponent<FreeConvectionParameters> {
 public:
  enum Input { kTemperature, kAmbient };
  enum Output { kHeatLoss };
  FreeConvection(std::string group, FreeConvectionParameters defaults,
                 ParameterBindings<FreeConvectionParameters> bindings = {});
  // Keys conductance, reference_difference, exponent (default 5/4).
  static std::unique_ptr<FreeConvection> from_config(const std::string& group,
                                                     const ConfigNode& node);
  // Q for a temperature difference dT [W].
  static double heat_loss(const FreeConvectionParameters& p, double difference);

  std::vector<OutputDeclaration> outputs() const override { return {{"heat_loss", "W"}}; }
  std::vector<InputDeclaration> inputs() const override {
    return {{"temperature", true}, {"ambient_temperature", true}};
  }
  void compute_outputs(const Evaluation& evaluation) const override;
};

}  // namespace tcpmsim
