#include "models/effects/effect_kinds.h"

#include "models/effects/free_convection.h"
#include "models/effects/maxwell_branch.h"
#include "models/effects/thermal_softening.h"
#include "models/muscle.h"

namespace tcpmsim {

namespace {

// A force term's four ports (its force affine in the deflection, now and at rest) into the
// muscle's fan-ins (SlsMechanics).
void connect_force_term(SystemBuilder& system, const MuscleAttachment& muscle) {
  system.connect(muscle.muscle + ".attached_stiffness", muscle.group + ".stiffness");
  system.connect(muscle.muscle + ".attached_force", muscle.group + ".offset_force");
  system.connect(muscle.muscle + ".attached_rest_stiffness", muscle.group + ".rest_stiffness");
  system.connect(muscle.muscle + ".attached_rest_force", muscle.group + ".rest_force");
}

void attach_maxwell_branch(const ConfigNode& section, const MuscleAttachment& muscle,
                           ScenarioBuilder& build) {
  SystemBuilder& system = build.system();
  auto& branch = system.add(MaxwellBranch::from_config(muscle.group, section));
  system.connect(branch, "deflection", muscle.muscle + ".deflection");
  system.connect(branch, "rest_deflection", muscle.muscle + ".rest_deflection");
  connect_force_term(system, muscle);
}

void attach_free_convection(const ConfigNode& section, const MuscleAttachment& muscle,
                            ScenarioBuilder& build) {
  if (!muscle.facts->thermal.heat_balance) {
    section.fail(
        "free convection needs a heat balance to attach to: use the physical thermal form "
        "(a thermal section and thermal_force.form: physical)");
  }
  SystemBuilder& system = build.system();
  auto& convection = system.add(FreeConvection::from_config(muscle.group, section));
  system.connect(convection, "temperature", muscle.muscle + ".temperature");
  system.connect(convection, "ambient_temperature", muscle.muscle + ".ambient_temperature");
  system.connect(muscle.muscle + ".heat_loss", muscle.group + ".heat_loss");
}

void attach_thermal_softening(const ConfigNode& section, const MuscleAttachment& muscle,
                              ScenarioBuilder& build) {
  if (!muscle.facts->thermal.reports_temperature) {
    section.fail(
        "a temperature-dependent stiffness needs the muscle's temperature: use the physical "
        "thermal form, or give the reduced form's thermal_force.force_per_kelvin");
  }
  SystemBuilder& system = build.system();
  auto& spring = system.add(ThermalSoftening::from_config(muscle.group, section));
  system.connect(spring, "temperature", muscle.muscle + ".temperature");
  system.connect(spring, "deflection", muscle.muscle + ".deflection");
  connect_force_term(system, muscle);
  muscle.facts->rest_force_attached = true;
}

}  // namespace

void register_effect_kinds(KindRegistry& kinds) {
  kinds.add({kEffectCategory,
             "maxwell_branch",
             "a spring in series with a dashpot, in parallel with the SLS: one more relaxation "
             "time c_b/k_b (generalized Maxwell solid)",
             {{example_muscle_scenario("  effects:\n    - {type: maxwell_branch, name: slow, "
                                       "stiffness: 1.5 mN/mm, damping: 30 mN*s/mm}\n",
                                       ""),
               "muscle.effects[0]"}},
             EffectBuilder(attach_maxwell_branch)});
  kinds.add({kEffectCategory,
             "free_convection",
             "laminar free convection, Q = G dT_ref (dT/dT_ref)^(5/4), in the thermal node's "
             "heat balance (physical form)",
             {{R"(scenario: {name: example, duration: 10 s}
output: {rate: 10 Hz}
muscle:
  thermal: {heat_capacity: 0.3 J/K, conductance: 0.01 W/K, ambient_temperature: 23 degC}
  thermal_force: {form: physical, force_per_kelvin: 0.004 N/K, reference_temperature: 23 degC}
  mechanics: {k1: 10.8e-3 N/mm, k2: 2.7e-3 N/mm, damping: 4.3e-3 N*s/mm, force_offset: 0.1 N}
  resistance: 10 ohm
  inductance: {quantity: measure, lambda_l: 2.81 mm, lambda_x: 28.8 mm, lambda_0: 0.433}
  effects:
    - {type: free_convection, name: still_air, conductance: 0.01 W/K, reference_difference: 50 K}
drive: {mode: power, power: 1 W}
load: {type: deflection, deflection: 20 mm}
)",
               "muscle.effects[0]"}},
             EffectBuilder(attach_free_convection)});
  kinds.add({kEffectCategory,
             "thermal_softening",
             "a spring in parallel with the SLS whose stiffness falls with temperature, "
             "s = max(0, s_ref (1 + alpha (T - T_ref))): a heated polymer softens",
             {{example_muscle_scenario(
                   "  effects:\n    - {type: thermal_softening, name: softening, "
                   "reference_stiffness: 5 mN/mm, temperature_coefficient: -0.01 1/K, "
                   "reference_temperature: 23 degC}\n",
                   ""),
               "muscle.effects[0]"}},
             EffectBuilder(attach_thermal_softening)});
}

}  // namespace tcpmsim
