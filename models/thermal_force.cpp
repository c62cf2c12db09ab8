#include "models/thermal_force.h"
#include "models/typical_values.h"

namespace tcpmsim {

PhysicalThermalForce::PhysicalThermalForce(
    std::string group, PhysicalThermalForceParameters defaults,
    ParameterBindings<PhysicalThermalForceParameters> bindings)
    : ParametricComponent(std::move(group), "thermal_force", defaults, std::move(bindings)) {}

std::unique_ptr<PhysicalThermalForce> PhysicalThermalForce::from_config(const std::string& group,
                                                                        const ConfigNode& node) {
  using P = PhysicalThermalForceParameters;
  node.declare({"form", "force_per_kelvin", "reference_temperature"});
  P p;
  ParameterBindings<P> bind;
  bind.quantity(node, "force_per_kelvin", "N/K", typical::force_per_kelvin({}), p,
                bind.member(&P::force_per_kelvin));
  bind.quantity(node, "reference_temperature", "K", typical::temperature(ValueCheck::positive()), p,
                bind.member(&P::reference_temperature));
  return std::make_unique<PhysicalThermalForce>(group, p, std::move(bind));
}

void PhysicalThermalForce::compute_outputs(const Evaluation& evaluation) const {
  const auto& p = run_parameters(evaluation);
  set_output(evaluation, kThermalForce,
             thermal_force::physical(p.force_per_kelvin, input(evaluation, kTemperature),
                                     p.reference_temperature));
}

ReducedThermalForce::ReducedThermalForce(std::string group, ReducedThermalForceParameters defaults,
                                         ParameterBindings<ReducedThermalForceParameters> bindings)
    : ParametricComponent(std::move(group), "reduced_thermal_force", defaults,
                          std::move(bindings)) {}

std::unique_ptr<ReducedThermalForce> ReducedThermalForce::from_config(const std::string& group,
                                                                      const ConfigNode& node) {
  using P = ReducedThermalForceParameters;
  node.declare({"form", "kappa_P", "kappa_c", "ambient_temperature", "force_per_kelvin",
                "initial_thermal_force"});
  P p;
  ParameterBindings<P> bind;
  bind.quantity(node, "kappa_P", "N/J", typical::heating_gain({}), p,
                bind.member(&P::heating_gain));
  bind.quantity(node, "kappa_c", "1/s", typical::cooling_rate(ValueCheck::positive()), p,
                bind.member(&P::cooling_rate));
  bind.quantity(node, "ambient_temperature", "K", typical::temperature(ValueCheck::positive()), p,
                bind.member(&P::ambient_temperature));
  if (auto phi = node.find("force_per_kelvin")) {
    p.force_per_kelvin = 0.0;
    bind.as_quantity(
        *phi, "N/K", {}, p, [](P& values) -> double& { return *values.force_per_kelvin; },
        [](double value) {
          return value == 0.0 ? std::string("expected a non-zero value (it divides the force)")
                              : std::string();
        });
  }
  bind.quantity_or(node, "initial_thermal_force", "N", 0.0, {}, p,
                   bind.member(&P::initial_thermal_force));
  return std::make_unique<ReducedThermalForce>(group, p, std::move(bind));
}

std::vector<OutputDeclaration> ReducedThermalForce::outputs() const {
  // The ambient temperature is a port for attached heat terms, not recorded (the parameter is).
  if (defaults().force_per_kelvin)
    return {
        {"thermal_force", "N"}, {"temperature", "K"}, {"ambient_temperature", "K", false, false}};
  return {{"thermal_force", "N"}};
}

void ReducedThermalForce::initialize(const Evaluation& evaluation,
                                     std::span<double> own_state) const {
  own_state[0] = run_parameters(evaluation).initial_thermal_force;
}

void ReducedThermalForce::compute_outputs(const Evaluation& evaluation) const {
  const auto& p = run_parameters(evaluation);
  const double thermal_force = state(evaluation, 0);
  set_output(evaluation, kThermalForce, thermal_force);
  if (p.force_per_kelvin) {
    set_output(
        evaluation, kTemperature,
        thermal_force::temperature(p.ambient_temperature, thermal_force, *p.force_per_kelvin));
    set_output(evaluation, kAmbientTemperature, p.ambient_temperature);
  }
}

void ReducedThermalForce::compute_derivatives(const Evaluation& evaluation,
                                              double* derivatives) const {
  const auto& p = run_parameters(evaluation);
  set_derivative(derivatives, 0,
                 thermal_force::rate(p.heating_gain, p.cooling_rate, state(evaluation, 0),
                                     input(evaluation, kPower) - input_sum(evaluation, kHeatLoss)));
  // (7.1)
}

}  // namespace tcpmsim
