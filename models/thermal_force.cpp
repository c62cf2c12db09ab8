#include "models/thermal_force.h"

namespace tcpmsim {

PhysicalThermalForce::PhysicalThermalForce(std::string group, double force_per_kelvin,
                                           double reference_temperature)
    : Component(std::move(group), "thermal_force"),
      force_per_kelvin_(force_per_kelvin),
      reference_temperature_(reference_temperature) {}

std::unique_ptr<PhysicalThermalForce> PhysicalThermalForce::from_config(const std::string& group,
                                                                        const ConfigNode& node) {
  node.declare({"form", "force_per_kelvin", "reference_temperature"});
  return std::make_unique<PhysicalThermalForce>(
      group, node.quantity("force_per_kelvin", "N/K"),
      node.quantity("reference_temperature", "K", ValueCheck::positive()));
}

void PhysicalThermalForce::compute_outputs(const Evaluation& evaluation) const {
  set_output(evaluation, kThermalForce,
             thermal_force::physical(force_per_kelvin_, input(evaluation, kTemperature),
                                     reference_temperature_));
}

ReducedThermalForce::ReducedThermalForce(std::string group,
                                         ReducedThermalForceParameters parameters)
    : Component(std::move(group), "reduced_thermal_force"), parameters_(parameters) {}

std::unique_ptr<ReducedThermalForce> ReducedThermalForce::from_config(const std::string& group,
                                                                      const ConfigNode& node) {
  node.declare({"form", "kappa_P", "kappa_c", "ambient_temperature", "force_per_kelvin",
                "initial_thermal_force"});
  ReducedThermalForceParameters p;
  p.heating_gain = node.quantity("kappa_P", "N/J");
  p.cooling_rate = node.quantity("kappa_c", "1/s", ValueCheck::positive());
  p.ambient_temperature = node.quantity("ambient_temperature", "K", ValueCheck::positive());
  if (auto phi = node.find("force_per_kelvin")) {
    p.force_per_kelvin = phi->as_quantity("N/K");
    if (*p.force_per_kelvin == 0.0) phi->fail("expected a non-zero value (it divides the force)");
  }
  p.initial_thermal_force = node.quantity_or("initial_thermal_force", "N", 0.0);
  return std::make_unique<ReducedThermalForce>(group, p);
}

std::vector<OutputDeclaration> ReducedThermalForce::outputs() const {
  if (parameters_.force_per_kelvin) return {{"thermal_force", "N"}, {"temperature", "K"}};
  return {{"thermal_force", "N"}};
}

void ReducedThermalForce::initialize(const Evaluation&, std::span<double> own_state) const {
  own_state[0] = parameters_.initial_thermal_force;
}

void ReducedThermalForce::compute_outputs(const Evaluation& evaluation) const {
  const double thermal_force = state(evaluation, 0);
  set_output(evaluation, kThermalForce, thermal_force);
  if (parameters_.force_per_kelvin) {
    set_output(evaluation, kTemperature,
               thermal_force::temperature(parameters_.ambient_temperature, thermal_force,
                                          *parameters_.force_per_kelvin));
  }
}

void ReducedThermalForce::compute_derivatives(const Evaluation& evaluation,
                                              double* derivatives) const {
  // (7.1)
  set_derivative(derivatives, 0,
                 thermal_force::rate(parameters_.heating_gain, parameters_.cooling_rate,
                                     state(evaluation, 0), input(evaluation, kPower)));
}

}  // namespace tcpmsim
