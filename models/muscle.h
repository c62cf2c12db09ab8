#pragma once

#include <functional>
#include <string>

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

// What a muscle tells the instances built after it (its drive, its load, its effects).
struct MuscleFacts {
  bool inductance_is_measure = false;  // (7.3) in the Muscle Drive's L*, not henries
  double lambda_x = 0.0;               // as built [m]
  SlsParameters mechanics;             // as built
  double initial_thermal_force = 0.0;  // F_T at t = 0 as built [N]
  // F_T at t = 0 in a run (its parameters and signals as the context has them).
  std::function<double(const Context&)> initial_thermal_force_in;
  bool heat_balance = false;         // a thermal node whose heat balance takes attached terms
  bool reports_temperature = false;  // <name>.temperature exists
  // An attached effect carries force at rest (a parallel spring): a static balance found from
  // k1, F_T and phi_0 alone would be wrong.
  bool rest_force_attached = false;
};

// What a thermal-force part kind builds and reports.
struct ThermalForm {
  double initial_thermal_force = 0.0;
  std::function<double(const Context&)> initial_thermal_force_in;
  bool reports_temperature = false;
  bool heat_balance = false;
};
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
