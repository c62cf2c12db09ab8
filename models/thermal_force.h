#pragma once

#include <memory>
#include <optional>

#include "sim/component.h"
#include "sim/config/config_node.h"

namespace tcpmsim {

// The thermal contribution to the muscle force, F_T in (7.5), in two forms.
//
// Physical form: F_T = phi_T (T - T_ref), with T from a thermal node.
//
// Reduced form (7.1): dF_T/dt = kappa_P P - kappa_c F_T, the thesis' identified model. It is
// the physical form with a linear thermal node C dT/dt = P - hA (T - T_amb) and
// T_ref = T_amb, rewritten in F_T:
//     kappa_c = hA / C,   kappa_P = phi_T / C   (and F_T = phi_T (T - T_amb)).
// Only the ratios are identifiable; given phi_T the reduced form can still report
// T = T_amb + F_T / phi_T.

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

struct ReducedThermalForceParameters {
  double heating_gain = 0.0;               // kappa_P [N/J]
  double cooling_rate = 0.0;               // kappa_c [1/s]
  double ambient_temperature = 0.0;        // [K], for the reported temperature
  std::optional<double> force_per_kelvin;  // phi_T [N/K], enables the temperature output
  double initial_thermal_force = 0.0;      // F_T(t0) [N]
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

// The mapping between the forms, documented above.
ReducedThermalForceParameters reduce_thermal_model(double heat_capacity, double conductance,
                                                   double force_per_kelvin,
                                                   double ambient_temperature);

}  // namespace tcpmsim
