#include "models/thermal_node.h"
#include "models/typical_values.h"

namespace tcpmsim {

namespace {
constexpr double kStefanBoltzmann = 5.670374419e-8;  // W m^-2 K^-4 (CODATA 2018, exact)
}  // namespace

ThermalNode::ThermalNode(std::string group, ThermalNodeParameters defaults,
                         ParameterBindings<ThermalNodeParameters> bindings,
                         std::unique_ptr<Signal> ambient_temperature)
    : ParametricComponent(std::move(group), "thermal_node", std::move(defaults),
                          std::move(bindings)),
      ambient_(std::move(ambient_temperature)) {}

std::unique_ptr<ThermalNode> ThermalNode::from_config(const std::string& group,
                                                      const ConfigNode& node,
                                                      const SignalContext& signals) {
  node.declare({"heat_capacity", "conductance", "ambient_temperature", "heating_efficiency",
                "radiation", "initial_temperature", "energy_accounting"});
  ThermalNodeParameters p;
  ParameterBindings<ThermalNodeParameters> bind;
  bind.quantity(node, "heat_capacity", "J/K", typical::heat_capacity(ValueCheck::positive()), p,
                bind.member(&ThermalNodeParameters::heat_capacity));
  bind.quantity(node, "conductance", "W/K", typical::conductance(ValueCheck::non_negative()), p,
                bind.member(&ThermalNodeParameters::conductance));
  bind.quantity_or(node, "heating_efficiency", "1", 1.0, ValueCheck::fraction(), p,
                   bind.member(&ThermalNodeParameters::heating_efficiency));
  if (auto radiation = node.find("radiation")) {
    bind.quantity(*radiation, "emissivity", "1", ValueCheck::fraction(), p,
                  bind.member(&ThermalNodeParameters::emissivity));
    bind.quantity(*radiation, "area", "m^2", typical::radiating_area(ValueCheck::positive()), p,
                  bind.member(&ThermalNodeParameters::radiating_area));
  }
  if (auto initial = node.find("initial_temperature")) {
    p.initial_temperature = 0.0;
    bind.as_quantity(
        *initial, "K", ValueCheck::positive(), p,
        [](ThermalNodeParameters& values) -> double& { return *values.initial_temperature; });
  }
  p.energy_accounting = node.boolean_or("energy_accounting", false);
  const ConfigNode ambient_node = node.at("ambient_temperature");
  auto ambient = read_signal(ambient_node, "K", signals);
  if (ambient->range(0.0, signals.duration).first <= 0.0) {
    ambient_node.fail("the ambient temperature must stay above 0 K");
  }
  return std::make_unique<ThermalNode>(group, p, std::move(bind), std::move(ambient));
}

std::vector<StateDeclaration> ThermalNode::states() const {
  std::vector<StateDeclaration> declared{{"temperature", "K", 1e-6}};
  if (defaults().energy_accounting) {
    declared.push_back({"heat_in", "J", 1e-9});
    declared.push_back({"heat_lost", "J", 1e-9});
  }
  return declared;
}

std::vector<OutputDeclaration> ThermalNode::outputs() const {
  std::vector<OutputDeclaration> declared{{"temperature", "K"}, {"ambient_temperature", "K"}};
  if (defaults().energy_accounting) {
    declared.push_back({"heat_in", "J"});
    declared.push_back({"heat_lost", "J"});
  }
  return declared;
}

std::vector<InputDeclaration> ThermalNode::inputs() const {
  return {{"power", false}, {"heat_loss", false, false, InputArity::many}};
}

std::vector<SignalDeclaration> ThermalNode::signals() const {
  return {{"ambient_temperature", "K", ambient_.get()}};
}

double ThermalNode::initial_temperature(double start_time) const {
  return defaults().initial_temperature.value_or(ambient_->value(start_time));
}

void ThermalNode::initialize(const Evaluation& evaluation, std::span<double> own_state) const {
  const auto& p = run_parameters(evaluation);
  own_state[kTemperatureState] =
      p.initial_temperature.value_or(signal(evaluation, 0).value(evaluation.signal_time));
  for (std::size_t i = 1; i < own_state.size(); ++i) own_state[i] = 0.0;
}

double ThermalNode::heat_loss(const ThermalNodeParameters& p, double temperature, double ambient) {
  const double convection = p.conductance * (temperature - ambient);
  if (p.emissivity == 0.0) return convection;
  const double t2 = temperature * temperature, a2 = ambient * ambient;
  return convection + p.emissivity * kStefanBoltzmann * p.radiating_area * (t2 * t2 - a2 * a2);
}

void ThermalNode::compute_outputs(const Evaluation& evaluation) const {
  set_output(evaluation, kTemperature, state(evaluation, kTemperatureState));
  set_output(evaluation, kAmbientTemperature, signal(evaluation, 0).value(evaluation.signal_time));
  if (defaults().energy_accounting) {
    set_output(evaluation, kHeatIn, state(evaluation, kHeatInState));
    set_output(evaluation, kHeatLost, state(evaluation, kHeatLostState));
  }
}

void ThermalNode::compute_derivatives(const Evaluation& evaluation, double* derivatives) const {
  const auto& p = run_parameters(evaluation);
  const double heating = p.heating_efficiency * input(evaluation, kPower);
  double loss = heat_loss(p, state(evaluation, kTemperatureState),
                          signal(evaluation, 0).value(evaluation.signal_time));
  if (source_count(kHeatLoss) > 0) loss += input_sum(evaluation, kHeatLoss);
  set_derivative(derivatives, kTemperatureState, (heating - loss) / p.heat_capacity);
  if (p.energy_accounting) {
    set_derivative(derivatives, kHeatInState, heating);
    set_derivative(derivatives, kHeatLostState, loss);
  }
}

double ThermalNode::next_breakpoint_after(const Evaluation& evaluation) const {
  return signal(evaluation, 0).next_breakpoint_after(evaluation.time);
}

}  // namespace tcpmsim
