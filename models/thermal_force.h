#pragma once

#include <memory>
#include <optional>

#include "models/laws/thermal_force.h"
#include "sim/component.h"
#include "sim/config/config_node.h"

namespace tcpmsim {

// The thermal force F_T of (7.5) as components, in the two forms of models/laws/thermal_force.h.

class PhysicalThermalForce final : public Component {
 public:
  enum Input { kTemperature };
  enum Output { kThermalForce };
  PhysicalThermalForce(std::string group, double force_per_kelvin, double reference_temperature);
  static std::unique_ptr<PhysicalThermalForce> from_config(const std::string& group,
                                                           const ConfigNode& node);

  std::vector<OutputDeclaration> outputs() const override { return {{"thermal_force", "N"}}; }
  std::vector<InputDeclaration> inputs() const override { return {{"temperature", true}}; }
  void compute_outputs(const Evaluation& evaluation) const override;

  double force_per_kelvin() const { return force_per_kelvin_; }
  double reference_temperature() const { return reference_temperature_; }

 private:
  double force_per_kelvin_;       // phi_T [N/K]
  double reference_temperature_;  // T_ref [K]
};

class ReducedThermalForce final : public Component {
 public:
  enum Input { kPower };
  enum Output { kThermalForce, kTemperature };
  ReducedThermalForce(std::string group, ReducedThermalForceParameters parameters);
  static std::unique_ptr<ReducedThermalForce> from_config(const std::string& group,
                                                          const ConfigNode& node);

  std::vector<StateDeclaration> states() const override { return {{"thermal_force", "N", 1e-10}}; }
  std::vector<OutputDeclaration> outputs() const override;
  std::vector<InputDeclaration> inputs() const override { return {{"power", false}}; }
  void initialize(const Evaluation& evaluation, std::span<double> own_state) const override;
  void compute_outputs(const Evaluation& evaluation) const override;
  void compute_derivatives(const Evaluation& evaluation, double* derivatives) const override;

  const ReducedThermalForceParameters& parameters() const { return parameters_; }

 private:
  ReducedThermalForceParameters parameters_;
};

}  // namespace tcpmsim
