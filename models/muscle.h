#pragma once

#include <functional>
#include <string>
#include <vector>

#include "models/laws/sls.h"
#include "sim/context.h"
#include "sim/registry.h"
#include "sim/scenario_builder.h"

namespace tcpmsim {

// A twisted and coiled polymer muscle as one instance (the category "muscle", kind "tcpm"): its
// thermal force (a part kind, "physical" with a thermal node or "reduced" (7.1)), its SLS
// mechanics (7.5)-(7.6), its coil impedance (6.3)-(6.5), and any effects attached to it.
//
// The instance's ports, for whatever drives and holds it:
//   inputs  <name>.power (heating, W), <name>.deflection, <name>.force or
//           <name>.cable_deflection (what the load imposes; a cable lets the muscle go slack)
//   outputs <name>.force, .deflection, .thermal_force, .temperature (if known), .resistance,
//           .inductance (or .inductance_measure), .stiffness and .rest_stiffness (dF/dx, 0 when
//           slack; ports only), ...
// and, for attached effects, <name>.attached_stiffness and <name>.attached_force (force terms
// affine in the deflection, see SlsMechanics), <name>.attached_rest_stiffness and
// <name>.attached_rest_force (the same at rest), the output <name>.rest_deflection, and
// <name>.heat_loss (physical form: a heat-loss term in W).

// What a thermal-force part kind builds and reports.
struct ThermalForm {
  double initial_thermal_force = 0.0;  // F_T at t = 0 as built [N]
  // F_T at t = 0 in a run (its parameters and signals as the context has them).
  std::function<double(const Context&)> initial_thermal_force_in;
  bool reports_temperature = false;  // <muscle>.temperature exists
  bool heat_balance = false;         // a thermal node whose heat balance takes attached terms
  // Attached heat terms (a heat loss beside the linear one) are taken: by the thermal node's
  // balance, or by (7.1) as power lost before it heats, kappa_P (P - Q), when the reduced form
  // reports a temperature for them to depend on.
  bool takes_heat_terms = false;
  // The muscle's temperature at t = 0 in a run, when it reports one [K].
  std::function<double(const Context&)> initial_temperature_in = {};
  double initial_temperature = 0.0;  // the same as built [K]
};

// A muscle at rest at the start: every dashpot relaxed (x_d = x) and F_T at its initial value.
// What a static balance of the muscles a load holds needs.
// The force an attached term carries with the muscle at rest at `deflection` [m] (a parallel
// spring at the starting temperature) [N].
using RestForce = std::function<double(double deflection)>;

struct RestingMuscle {
  SlsParameters mechanics;
  double thermal_force = 0.0;            // F_T(0) [N]
  std::vector<RestForce> attached = {};  // the terms that carry force at rest
  // (7.5) with x_d = x: k1 x + F_T + phi_0, and the attached terms' rest forces.
  double force(double deflection) const {
    double total = sls::total_force(
        mechanics, sls::elastic_force(mechanics, deflection, deflection), thermal_force);
    for (const auto& term : attached) total += term(deflection);
    return total;
  }
};

// What a muscle tells the instances built after it (its drive, its load, its effects).
struct MuscleFacts {
  bool has_inductance = true;          // false: no self-sensing key, no inductance output
  bool inductance_is_measure = false;  // (7.3) in the Muscle Drive's L*, not henries
  double lambda_x = 0.0;               // as built [m]
  ThermalForm thermal;                 // its thermal part, as built
  RestingMuscle resting;               // at the start, as built
  std::function<RestingMuscle(const Context&)> resting_in;  // the same in a run
  // An attached effect carries force at rest (a parallel spring): a balance that reads only
  // k1, F_T and phi_0 (a joint's) would be wrong. Such an effect adds its rest force, as built
  // and in a run, and the muscle adds them to `resting` and `resting_in`.
  bool rest_force_attached = false;
  std::vector<RestForce> rest_forces = {};
  std::vector<std::function<RestForce(const Context&)>> rest_forces_in = {};
};

// A load whose start `value` is its muscles' static balance (RestingMuscle) refuses, located at
// `value`, a muscle with an attached effect that carries force at rest; `give` names what to give
// instead ("the deflection").
void check_resting_balance(const ConfigNode& value, const std::string& muscle,
                           const MuscleFacts& facts, const std::string& give);

// Builds the thermal part of muscle `muscle` from the muscle's section, wiring <muscle>.power.
using ThermalFormBuilder = std::function<ThermalForm(
    const ConfigNode& muscle_section, const std::string& muscle, ScenarioBuilder& build)>;

// What an effect attached to a muscle is told.
struct MuscleAttachment {
  std::string muscle;  // the instance
  std::string group;   // the effect's own group, "<muscle>/<effect name>"
  MuscleFacts* facts;  // an effect may add to them (rest_force_attached)
};
// Builds an effect from its section under the muscle's `effects`.
using EffectBuilder = std::function<void(const ConfigNode& section, const MuscleAttachment& muscle,
                                         ScenarioBuilder& build)>;

inline constexpr const char* kMuscleCategory = "muscle";
inline constexpr const char* kThermalForceCategory = "thermal_force";
inline constexpr const char* kEffectCategory = "effect";

// Registers the categories muscle (kind tcpm), thermal_force (physical, reduced) and effect.
void register_muscle_kinds(KindRegistry& kinds);

// A whole scenario with one muscle (Table 7.2's, reduced form) in which `muscle_extra` is
// appended to the muscle's section and `rest` to the scenario: for the kinds' examples.
std::string example_muscle_scenario(const std::string& muscle_extra, const std::string& rest);

}  // namespace tcpmsim
