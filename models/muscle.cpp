#include "models/muscle.h"

#include <set>
#include <stdexcept>

#include "models/coil_impedance.h"
#include "models/effects/effect_candidates.h"
#include "models/laws/thermal_force.h"
#include "models/sls_mechanics.h"
#include "models/thermal_force.h"
#include "models/thermal_node.h"

namespace tcpmsim {

namespace {

ThermalForm build_reduced(const ConfigNode& muscle, const std::string& name,
                          ScenarioBuilder& build) {
  if (muscle.has("thermal")) {
    muscle.at("thermal").fail("the reduced thermal form (7.1) has no thermal node; remove " +
                              muscle.path() + ".thermal or use thermal_force.form: physical");
  }
  auto& reduced =
      build.system().add(ReducedThermalForce::from_config(name, muscle.at("thermal_force")));
  build.system().export_input(name + ".power", reduced, "power");
  build.system().export_input(name + ".heat_loss", reduced, "heat_loss");
  const std::string initial = name + ".thermal_force.initial_thermal_force";
  const bool temperature = reduced.defaults().force_per_kelvin.has_value();
  ThermalForm form{reduced.defaults().initial_thermal_force,
                   [initial](const Context& context) { return context.parameter(initial); },
                   temperature, false, temperature};
  if (temperature) {  // T = T_amb + F_T / phi_T
    const auto& p = reduced.defaults();
    form.initial_temperature =
        p.ambient_temperature + p.initial_thermal_force / *p.force_per_kelvin;
    const std::string section = name + ".thermal_force.";
    form.initial_temperature_in = [section](const Context& context) {
      return context.parameter(section + "ambient_temperature") +
             context.parameter(section + "initial_thermal_force") /
                 context.parameter(section + "force_per_kelvin");
    };
  }
  return form;
}

ThermalForm build_physical(const ConfigNode& muscle, const std::string& name,
                           ScenarioBuilder& build) {
  auto& node =
      build.system().add(ThermalNode::from_config(name, muscle.at("thermal"), build.signals()));
  build.system().export_input(name + ".power", node, "power");
  build.system().export_input(name + ".heat_loss", node, "heat_loss");
  auto& force =
      build.system().add(PhysicalThermalForce::from_config(name, muscle.at("thermal_force")));
  build.system().connect(force, "temperature", name + ".temperature");
  // The thermal node starts at its initial temperature; F_T follows from it.
  const double initial =
      thermal_force::physical(force.defaults().force_per_kelvin, node.initial_temperature(0.0),
                              force.defaults().reference_temperature);
  const bool given = node.defaults().initial_temperature.has_value();
  auto start = [name, given](const Context& context) {
    return given ? context.parameter(name + ".thermal.initial_temperature")
                 : context.signal(*context.system().signal_slot(name, "ambient_temperature"))
                       .value(0.0);
  };
  auto in_run = [name, start](const Context& context) {
    return thermal_force::physical(
        context.parameter(name + ".thermal_force.force_per_kelvin"), start(context),
        context.parameter(name + ".thermal_force.reference_temperature"));
  };
  return {initial, in_run, true, true, true, start, node.initial_temperature(0.0)};
}

void build_effects(const ConfigNode& muscle, const std::string& name, MuscleFacts& facts,
                   ScenarioBuilder& build) {
  const auto effects = muscle.find("effects");
  if (!effects) return;
  effects->mark_part("list of effects: " + [&] {
    std::string listed;
    for (const auto& kind : build.kinds().kind_names(kEffectCategory))
      listed += (listed.empty() ? "" : ", ") + kind;
    return listed;
  }());
  std::set<std::string> names;
  for (const auto& section : effects->elements()) {
    const Kind& kind = build.kinds().select(kEffectCategory, section);
    const std::string effect = section.has("name") ? section.text("name") : kind.name;
    if (effect.empty() || effect.find_first_of("./[] \t") != std::string::npos)
      section.at("name").fail("expected a name without dots, slashes, brackets or spaces");
    if (!names.insert(effect).second) {
      section.fail("two effects of " + name + " are named '" + effect +
                   "'; give each a different `name`");
    }
    const MuscleAttachment attachment{name, name + "/" + effect, &facts};
    build.kinds().builder<EffectBuilder>(kind)(section, attachment, build);
  }
}

// The example scenario with a constant resistance.
std::string replaced_resistance(std::string scenario) {
  const std::string from = "  resistance: {form: linear";
  const auto start = scenario.find(from);
  if (start == std::string::npos)
    throw std::logic_error("the example muscle no longer has a linear resistance to replace");
  const auto end = scenario.find('\n', start);
  return scenario.replace(start, end - start, "  resistance: 10.18 ohm");
}

void build_muscle(const ConfigNode& muscle, const std::string& name, ScenarioBuilder& build) {
  muscle.declare({"thermal", "thermal_force", "mechanics", "resistance", "inductance", "effects"});
  SystemBuilder& system = build.system();
  const Kind& form = build.kinds().select(kThermalForceCategory, muscle.at("thermal_force"));
  const ThermalForm thermal = build.kinds().builder<ThermalFormBuilder>(form)(muscle, name, build);

  auto& mechanics = system.add(SlsMechanics::from_config(name, muscle.at("mechanics")));
  system.connect(mechanics, "thermal_force", name + ".thermal_force");
  for (const char* port : {"deflection", "force", "attached_stiffness", "attached_force",
                           "attached_rest_stiffness", "attached_rest_force", "cable_deflection"})
    system.export_input(name + "." + port, mechanics, port);

  const ConfigNode resistance = muscle.at("resistance");
  // The coil's inductance (6.3)/(7.3) only where something reads it: self-sensing.
  const std::optional<ConfigNode> inductance = muscle.find("inductance");
  auto& coil = system.add(CoilImpedance::from_config(name, inductance, resistance));
  system.connect(coil, "deflection", name + ".deflection");
  system.export_input(name + ".mutual_inductances", coil, "mutual_inductances");
  if (coil.needs_temperature()) {
    if (!thermal.reports_temperature) {
      (coil.defaults().resistance_law().rho_T != 0.0 || !inductance ? resistance : *inductance)
          .fail("depends on temperature, but the reduced thermal form reports none; give " +
                muscle.path() + ".thermal_force.force_per_kelvin");
    }
    system.connect(coil, "temperature", name + ".temperature");
  }

  MuscleFacts facts;
  facts.has_inductance = coil.has_inductance();
  facts.inductance_is_measure = coil.defaults().inductance.is_measure;
  facts.lambda_x = coil.defaults().inductance.lambda_x;
  facts.thermal = thermal;
  facts.resting = {mechanics.defaults(), thermal.initial_thermal_force};
  facts.resting_in = [sls = &mechanics,
                      thermal_force = thermal.initial_thermal_force_in](const Context& context) {
    return RestingMuscle{sls->parameters_in(context), thermal_force(context)};
  };
  build_effects(muscle, name, facts, build);
  // The attached terms' rest forces join the muscle's at rest.
  facts.resting.attached = facts.rest_forces;
  if (!facts.rest_forces_in.empty()) {
    facts.resting_in = [base = facts.resting_in,
                        terms = facts.rest_forces_in](const Context& context) {
      RestingMuscle resting = base(context);
      for (const auto& term : terms) resting.attached.push_back(term(context));
      return resting;
    };
  }
  build.publish(name, facts);
}

}  // namespace

void check_resting_balance(const ConfigNode& value, const std::string& muscle,
                           const MuscleFacts& facts, const std::string& give) {
  if (facts.rest_force_attached) {
    value.fail("the equilibrium is found from k1, F_T and phi_0 alone, but " + muscle +
               " has an effect that carries force at rest; give " + give);
  }
}

namespace {

// The coil law's own lambda_T (T - T_ref) term, zero in a base model without it: a coil built
// without it has no temperature input, so the candidate's scenario gives it a value and the
// refit starts it at zero (models/effects/effect_candidates.h).
CandidateDeclaration coil_term_candidates() {
  using S = CandidateScale;
  CandidateMember term{"lambda_T (T - T_ref)",
                       1,
                       {{{"lambda_T", "", scaled(0.0, S::coil_scale), scaled(-0.01, S::coil_scale),
                          scaled(0.01, S::coil_scale)}}},
                       {},
                       CandidateLawTerm{"inductance", scaled(1e-5, S::coil_scale)}};
  return {{{"inductance_temperature",
            6,
            "the inductance measure depends on temperature",
            "L* residual against temperature",
            {CandidateNeed::coil_output, CandidateNeed::coil_temperature_term},
            {term}}},
          ""};
}

}  // namespace

void register_muscle_kinds(KindRegistry& kinds) {
  kinds.add_category({kMuscleCategory, "muscles", "", "",
                      "a twisted and coiled polymer muscle: thermal force, SLS mechanics and "
                      "coil impedance",
                      "", 20});
  kinds.add_category({kThermalForceCategory, "", "form", "",
                      "a muscle's thermal force F_T of (7.5), under muscle.thermal_force", "", 0});
  kinds.add_category({kEffectCategory, "", "type", "",
                      "a physical effect attached to a muscle (muscle.effects: [...]): a further "
                      "force branch or heat-loss law the base components do not know",
                      "", 0});
  const std::string physical = R"(scenario: {name: example, duration: 10 s}
output: {rate: 10 Hz}
muscle:
  thermal:
    heat_capacity: 0.3 J/K
    conductance: 0.02 W/K
    ambient_temperature: 23 degC
    heating_efficiency: 0.9
    radiation: {emissivity: 0.9, area: 1.5 cm^2}
    initial_temperature: 30 degC
    energy_accounting: true
  thermal_force: {form: physical, force_per_kelvin: 0.004 N/K, reference_temperature: 0 degC}
  mechanics: {k1: 10.8e-3 N/mm, k2: 2.7e-3 N/mm, damping: 4.3e-3 N*s/mm, force_offset: -0.075 N}
  resistance: {form: thermal, resistance: 9.4 ohm, temperature_coefficient: 6.41e-3 1/K, reference_temperature: 23 degC, strain_coefficient: -0.005 ohm/mm}
  inductance: {lambda_l: 107.4 uH*mm, lambda_x: 61 mm, lambda_T: 0.008 uH/K, lambda_0: 2.67 uH, reference_temperature: 0 degC}
drive: {mode: power, power: 1 W}
load: {type: deflection, deflection: 20 mm}
)";
  const std::string constant_resistance = replaced_resistance(example_muscle_scenario(
      "  effects: [{type: maxwell_branch, stiffness: 1 N/m, damping: 10 N*s/m}]\n", ""));
  kinds.add({kMuscleCategory,
             "tcpm",
             "thermal force (7.1) or a thermal node, SLS (7.5)-(7.6), coil (6.3)-(6.5): "
             "resistance a constant, linear (6.5) or thermal (6.4); inductance (6.3) in henries "
             "or (7.3) as L*",
             {{example_muscle_scenario("", ""), "muscle"},
              {physical, "muscle"},
              {constant_resistance, "muscle"}},
             InstanceBuilder(build_muscle),
             coil_term_candidates()});
  kinds.add({kThermalForceCategory,
             "physical",
             "F_T = phi_T (T - T_ref) with a thermal node C dT/dt = eta P - hA (T - T_amb) - "
             "eps sigma A (T^4 - T_amb^4) (muscle.thermal)",
             {{physical, "muscle.thermal_force"}, {physical, "muscle.thermal"}},
             ThermalFormBuilder(build_physical)});
  kinds.add({kThermalForceCategory,
             "reduced",
             "(7.1) dF_T/dt = kappa_P P - kappa_c F_T; with force_per_kelvin it reports "
             "T = T_amb + F_T / phi_T",
             {{example_muscle_scenario("", ""), "muscle.thermal_force"}},
             ThermalFormBuilder(build_reduced)});
}

std::string example_muscle_scenario(const std::string& muscle_extra, const std::string& rest) {
  return R"(scenario: {name: example, duration: 10 s, seed: 1}
output: {rate: 10 Hz}
muscle:
  thermal_force: {form: reduced, kappa_P: 7.2e-3 N/J, kappa_c: 131.6e-3 1/s, ambient_temperature: 23 degC, force_per_kelvin: 4 mN/K, initial_thermal_force: 0 N}
  mechanics: {k1: 10.8e-3 N/mm, k2: 2.7e-3 N/mm, damping: 4.3e-3 N*s/mm, force_offset: 106.9e-3 N}
  resistance: {form: linear, rho_x: -0.005 ohm/mm, rho_T: 0.03 ohm/K, rho_0: 10.18 ohm, reference_temperature: 0 degC}
  inductance: {quantity: measure, lambda_l: 2.81 mm, lambda_x: 28.8 mm, lambda_0: 0.433}
)" + muscle_extra +
         (rest.empty()
              ? "drive: {mode: power, power: 1 W}\nload: {type: deflection, deflection: 20 mm}\n"
              : rest);
}

}  // namespace tcpmsim
