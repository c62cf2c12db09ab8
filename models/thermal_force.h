#pragma once

#include <memory>
#include <optional>

#include "models/laws/thermal_force.h"
#include "sim/config/config_node.h"
#include "sim/parametric_component.h"

namespace tcpmsim {

// The thermal force F_T of (7.5) as components, in the two forms of models/laws/thermal_force.h.

struct PhysicalThermalForceParameters {
  double force_per_kelvin = 0.0;       // phi_T [N/K]
  double reference_temperature = 0.0;  // T_ref [K]
};

// F_T = phi_T (T - T_ref), with T from a thermal node.
class PhysicalThermalForce final : public ParametricComponent<PhysicalThermalForceParameters> {
 public:
  enum Input { kTemperature };
  enum Output { kThermalForce };
  PhysicalThermalForce(std::string group, PhysicalThermalForceParameters defaults,
                       ParameterBindings<PhysicalThermalForceParameters> bindings = {});
  static std::unique_ptr<PhysicalThermalForce> from_config(const std::string& group,
                                                           const ConfigNode& node);

  std::vector<OutputDeclaration> outputs() const override { return {{"thermal_force", "N"}}; }
  std::vector<InputDeclaration> inputs() const override { return {{"temperature", true}}; }
  void compute_outputs(const Evaluation& evaluation) const override;
};

// (7.1): dF_T/dt = kappa_P P - kappa_c F_T, with F_T as the state.
class ReducedThermalForce final : public ParametricComponent<ReducedThermalForceParameters> {
 public:
  enum Input { kPower, kHeatLoss };
  enum Output { kThermalForce, kTemperature, kAmbientTemperature };
  ReducedThermalForce(std::string group, ReducedThermalForceParameters defaults,
                      ParameterBindings<ReducedThermalForceParameters> bindings = {});
  static std::unique_ptr<ReducedThermalForce> from_config(const std::string& group,
                                                          const ConfigNode& node);

  std::vector<StateDeclaration> states() const override { return {{"thermal_force", "N", 1e-10}}; }
  std::vector<OutputDeclaration> outputs() const override;
  // Attached heat terms Q (a fan-in, none by default) take their share of the power before it
  // heats: dF_T/dt = kappa_P (P - sum Q) - kappa_c F_T.
  std::vector<InputDeclaration> inputs() const override {
    return {{"power", false}, {"heat_loss", false, false, InputArity::many}};
  }
  void initialize(const Evaluation& evaluation, std::span<double> own_state) const override;
  void compute_outputs(const Evaluation& evaluation) const override;
  void compute_derivatives(const Evaluation& evaluation, double* derivatives) const override;
};

}  // namespace tcpmsim
