#include "models/coil_impedance.h"
#include "models/typical_values.h"

namespace tcpmsim {

namespace {

void read_inductance(const ConfigNode& node, CoilImpedanceParameters& p,
                     ParameterBindings<CoilImpedanceParameters>& bind) {
  node.declare(
      {"quantity", "lambda_l", "lambda_x", "lambda_T", "lambda_0", "reference_temperature"});
  InductanceLaw& law = p.inductance;
  law.is_measure = node.choice_or("quantity", {"inductance", "measure"}, "inductance") == "measure";
  const char* per_length = law.is_measure ? "m" : "H*m";
  const char* value = law.is_measure ? "1" : "H";
  const char* per_kelvin = law.is_measure ? "1/K" : "H/K";
  bind.quantity(node, "lambda_l", per_length, ValueCheck::positive(), p,
                [](CoilImpedanceParameters& v) -> double& { return v.inductance.lambda_l; });
  bind.quantity(node, "lambda_x", "m", ValueCheck::positive(), p,
                [](CoilImpedanceParameters& v) -> double& { return v.inductance.lambda_x; });
  bind.quantity(node, "lambda_0", value, {}, p,
                [](CoilImpedanceParameters& v) -> double& { return v.inductance.lambda_0; });
  bind.quantity_or(node, "lambda_T", per_kelvin, 0.0, {}, p,
                   [](CoilImpedanceParameters& v) -> double& { return v.inductance.lambda_T; });
  if (law.lambda_T != 0.0) {
    bind.quantity(
        node, "reference_temperature", "K", ValueCheck::positive(), p,
        [](CoilImpedanceParameters& v) -> double& { return v.inductance.reference_temperature; });
  }
}

void read_resistance(const ConfigNode& node, CoilImpedanceParameters& p,
                     ParameterBindings<CoilImpedanceParameters>& bind) {
  if (node.is_scalar()) {
    p.resistance_form = CoilImpedanceParameters::ResistanceForm::constant;
    p.resistance = {0.0, 0.0, 0.0, 273.15};
    bind.as_quantity(node, "ohm", ValueCheck::positive(), p,
                     [](CoilImpedanceParameters& v) -> double& { return v.resistance.rho_0; });
    return;
  }
  node.declare({"form", "rho_x", "rho_T", "rho_0", "reference_temperature", "resistance",
                "temperature_coefficient", "strain_coefficient"});
  const std::string form = node.choice("form", {"linear", "thermal"});
  if (form == "thermal") {
    p.resistance_form = CoilImpedanceParameters::ResistanceForm::thermal;
    bind.quantity(node, "resistance", "ohm", typical::resistance(ValueCheck::positive()), p,
                  bind.member(&CoilImpedanceParameters::thermal_resistance));
    bind.quantity(node, "temperature_coefficient", "1/K", {}, p,
                  bind.member(&CoilImpedanceParameters::temperature_coefficient));
    bind.quantity(node, "reference_temperature", "K", ValueCheck::positive(), p,
                  bind.member(&CoilImpedanceParameters::thermal_reference));
    bind.quantity_or(node, "strain_coefficient", "ohm/m", 0.0, {}, p,
                     bind.member(&CoilImpedanceParameters::strain_coefficient));
    return;
  }
  p.resistance_form = CoilImpedanceParameters::ResistanceForm::linear;
  bind.quantity(node, "rho_x", "ohm/m", {}, p,
                [](CoilImpedanceParameters& v) -> double& { return v.resistance.rho_x; });
  bind.quantity(node, "rho_T", "ohm/K", {}, p,
                [](CoilImpedanceParameters& v) -> double& { return v.resistance.rho_T; });
  bind.quantity(node, "rho_0", "ohm", {}, p,
                [](CoilImpedanceParameters& v) -> double& { return v.resistance.rho_0; });
  bind.quantity(
      node, "reference_temperature", "K", ValueCheck::positive(), p,
      [](CoilImpedanceParameters& v) -> double& { return v.resistance.reference_temperature; });
}
}  // namespace

ResistanceLaw CoilImpedanceParameters::resistance_law() const {
  if (resistance_form != ResistanceForm::thermal) return resistance;
  return ResistanceLaw::thermal(thermal_resistance, temperature_coefficient, thermal_reference,
                                strain_coefficient);
}

struct CoilImpedance::Run final : RunState {
  InductanceLaw inductance;
  ResistanceLaw resistance;
};

CoilImpedance::CoilImpedance(std::string group, CoilImpedanceParameters defaults,
                             ParameterBindings<CoilImpedanceParameters> bindings)
    : Component(std::move(group), "coil_impedance"),
      defaults_(defaults),
      bindings_(std::move(bindings)),
      temperature_dependent_(defaults_.inductance.lambda_T != 0.0 ||
                             defaults_.resistance_law().rho_T != 0.0) {}

std::unique_ptr<CoilImpedance> CoilImpedance::from_config(
    const std::string& group, const std::optional<ConfigNode>& inductance,
    const ConfigNode& resistance) {
  CoilImpedanceParameters p;
  ParameterBindings<CoilImpedanceParameters> bind;
  read_resistance(resistance, p, bind);
  p.has_inductance = inductance.has_value();
  if (inductance) read_inductance(*inductance, p, bind);
  return std::make_unique<CoilImpedance>(group, p, std::move(bind));
}

std::vector<OutputDeclaration> CoilImpedance::outputs() const {
  if (!has_inductance()) return {{"resistance", "ohm"}};
  return {defaults_.inductance.is_measure ? OutputDeclaration{"inductance_measure", "1"}
                                          : OutputDeclaration{"inductance", "H"},
          {"resistance", "ohm"}};
}

std::vector<InputDeclaration> CoilImpedance::inputs() const {
  const InputDeclaration mutual{"mutual_inductances", true, false, InputArity::many, true};
  if (needs_temperature()) return {{"deflection", true}, {"temperature", true}, mutual};
  return {{"deflection", true}, mutual};
}

std::string CoilImpedance::check_connections() const {
  if (source_count(mutual_input()) > 0 && !has_inductance())
    return "couples the coil to its neighbours, but the muscle states no inductance: give its "
           "inductance";
  if (source_count(mutual_input()) > 0 && defaults_.inductance.is_measure)
    return "adds mutual inductances in henries to an inductance given as the measure L*";
  return {};
}

std::vector<ParameterDeclaration> CoilImpedance::parameters() const {
  return bindings_.declarations(defaults_);
}

std::unique_ptr<RunState> CoilImpedance::create_run_state(const RunSetup& setup) const {
  const CoilImpedanceParameters p = bindings_.assign(defaults_, setup.parameters);
  auto run = std::make_unique<Run>();
  run->inductance = p.inductance;
  run->resistance = p.resistance_law();
  return run;
}

std::string CoilImpedance::check_parameters(const RunSetup& setup) const {
  const CoilImpedanceParameters p = bindings_.assign(defaults_, setup.parameters);
  if (!needs_temperature() && (p.inductance.lambda_T != 0.0 || p.resistance_law().rho_T != 0.0)) {
    return "the coil was built without a temperature input; a run cannot make it "
           "temperature-dependent (give the dependence in the scenario)";
  }
  return {};
}

void CoilImpedance::compute_outputs(const Evaluation& evaluation) const {
  const auto& run = run_state<Run>(evaluation);
  const double deflection = input(evaluation, kDeflection);
  const double temperature = needs_temperature() ? input(evaluation, kTemperature) : 0.0;
  if (!has_inductance()) {
    set_output(evaluation, kInductance, run.resistance(deflection, temperature));  // its only
    return;
  }
  double inductance = run.inductance(deflection, temperature);
  if (source_count(mutual_input()) > 0) inductance += input_sum(evaluation, mutual_input());
  set_output(evaluation, kInductance, inductance);
  set_output(evaluation, kResistance, run.resistance(deflection, temperature));
}

}  // namespace tcpmsim
