#include "models/thermal_node.h"

#include "signals/signal_config.h"

namespace tcpmsim {

namespace {
constexpr double kStefanBoltzmann = 5.670374419e-8;  // W m^-2 K^-4 (CODATA 2018, exact)
}

ThermalNode::ThermalNode(std::string group, ThermalNodeParameters parameters,
                         std::unique_ptr<Signal> ambient_temperature)
    : Component(std::move(group), "thermal_node"),
      parameters_(parameters),
      ambient_(std::move(ambient_temperature)) {}

std::unique_ptr<ThermalNode> ThermalNode::from_config(const std::string& group,
                                                      const ConfigNode& node,
                                                      const SignalContext& signals) {
  node.declare({"heat_capacity", "conductance", "ambient_temperature", "heating_efficiency",
                "radiation", "initial_temperature", "energy_accounting"});
  ThermalNodeParameters p;
  p.heat_capacity = node.quantity("heat_capacity", "J/K", ValueCheck::positive());
  p.conductance = node.quantity("conductance", "W/K", ValueCheck::non_negative());
  p.heating_efficiency = node.number_or("heating_efficiency", 1.0, ValueCheck::fraction());
  if (auto radiation = node.find("radiation")) {
    p.emissivity = radiation->number("emissivity", ValueCheck::fraction());
    p.radiating_area = radiation->quantity("area", "m^2", ValueCheck::positive());
  }
  if (auto initial = node.find("initial_temperature")) {
    p.initial_temperature = initial->as_quantity("K", ValueCheck::positive());
  }
  p.energy_accounting = node.boolean_or("energy_accounting", false);
  const ConfigNode ambient_node = node.at("ambient_temperature");
  auto ambient = read_signal(ambient_node, "K", signals);
  if (ambient->range(0.0, signals.duration).first <= 0.0) {
    ambient_node.fail("the ambient temperature must stay above 0 K");
  }
  return std::make_unique<ThermalNode>(group, p, std::move(ambient));
}

std::vector<StateDeclaration> ThermalNode::states() const {
  std::vector<StateDeclaration> declared{{"temperature", "K", 1e-6}};
  if (parameters_.energy_accounting) {
    declared.push_back({"heat_in", "J", 1e-9});
    declared.push_back({"heat_lost", "J", 1e-9});
  }
  return declared;
}

std::vector<OutputDeclaration> ThermalNode::outputs() const {
  std::vector<OutputDeclaration> declared{{"temperature", "K"}, {"ambient_temperature", "K"}};
  if (parameters_.energy_accounting) {
    declared.push_back({"heat_in", "J"});
    declared.push_back({"heat_lost", "J"});
  }
  return declared;
}

std::vector<InputDeclaration> ThermalNode::inputs() const {
  return {{"power", false}};
}

double ThermalNode::initial_temperature(double start_time) const {
  return parameters_.initial_temperature.value_or(ambient_->value(start_time));
}

void ThermalNode::initialize(const Evaluation& evaluation, std::span<double> own_state) const {
  own_state[kTemperatureState] = initial_temperature(evaluation.signal_time);
  for (std::size_t i = 1; i < own_state.size(); ++i) own_state[i] = 0.0;
}

double ThermalNode::heat_loss(double temperature, double ambient) const {
  const double convection = parameters_.conductance * (temperature - ambient);
  if (parameters_.emissivity == 0.0) return convection;
  const double t2 = temperature * temperature, a2 = ambient * ambient;
  return convection + parameters_.emissivity * kStefanBoltzmann * parameters_.radiating_area *
                          (t2 * t2 - a2 * a2);
}

void ThermalNode::compute_outputs(const Evaluation& evaluation) const {
  set_output(evaluation, kTemperature, state(evaluation, kTemperatureState));
  set_output(evaluation, kAmbientTemperature, ambient_->value(evaluation.signal_time));
  if (parameters_.energy_accounting) {
    set_output(evaluation, kHeatIn, state(evaluation, kHeatInState));
    set_output(evaluation, kHeatLost, state(evaluation, kHeatLostState));
  }
}

void ThermalNode::compute_derivatives(const Evaluation& evaluation, double* derivatives) const {
  const double heating = parameters_.heating_efficiency * input(evaluation, kPower);
  const double loss =
      heat_loss(state(evaluation, kTemperatureState), ambient_->value(evaluation.signal_time));
  set_derivative(derivatives, kTemperatureState, (heating - loss) / parameters_.heat_capacity);
  if (parameters_.energy_accounting) {
    set_derivative(derivatives, kHeatInState, heating);
    set_derivative(derivatives, kHeatLostState, loss);
  }
}

double ThermalNode::next_breakpoint_after(double t) const {
  return ambient_->next_breakpoint_after(t);
}

std::vector<Component::SignalRecord> ThermalNode::signal_records() const {
  return {{"ambient_temperature", "K", ambient_.get()}};
}

}  // namespace tcpmsim
