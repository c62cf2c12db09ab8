#include "models/effects/effect_kinds.h"

#include "models/effects/free_convection.h"
#include "models/effects/maxwell_branch.h"
#include "models/muscle.h"

namespace tcpmsim {

namespace {

void attach_maxwell_branch(const ConfigNode& section, const MuscleAttachment& muscle,
                           ScenarioBuilder& build) {
  SystemBuilder& system = build.system();
  auto& branch = system.add(MaxwellBranch::from_config(muscle.group, section));
  system.connect(branch, "deflection", muscle.muscle + ".deflection");
  system.connect(branch, "rest_deflection", muscle.muscle + ".rest_deflection");
  system.connect(muscle.muscle + ".attached_stiffness", muscle.group + ".stiffness");
  system.connect(muscle.muscle + ".attached_force", muscle.group + ".offset_force");
  system.connect(muscle.muscle + ".attached_rest_stiffness", muscle.group + ".rest_stiffness");
  system.connect(muscle.muscle + ".attached_rest_force", muscle.group + ".rest_force");
}

void attach_free_convection(const ConfigNode& section, const MuscleAttachment& muscle,
                            ScenarioBuilder& build) {
  if (!muscle.facts->heat_balance) {
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
}

}  // namespace tcpmsim
