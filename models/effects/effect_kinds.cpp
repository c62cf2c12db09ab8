#include "models/effects/effect_kinds.h"

#include "models/effects/effect_candidates.h"
#include "models/effects/free_convection.h"
#include "models/effects/heat_sink.h"
#include "models/effects/heating_convection.h"
#include "models/effects/heating_lag.h"
#include "models/effects/hysteresis.h"
#include "models/effects/maxwell_branch.h"
#include "models/effects/nonlinear_stiffness.h"
#include "models/effects/ratchet.h"
#include "models/effects/thermal_lag.h"
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

// A force term with a state that follows the muscle's deflection from its rest deflection.
void connect_deflection_term(SystemBuilder& system, const Component& term,
                             const MuscleAttachment& muscle) {
  system.connect(term, "deflection", muscle.muscle + ".deflection");
  system.connect(term, "rest_deflection", muscle.muscle + ".rest_deflection");
  connect_force_term(system, muscle);
}

// A term driven by the muscle's temperature, which the reduced form reports only with its
// force_per_kelvin.
void require_temperature(const ConfigNode& section, const MuscleAttachment& muscle,
                         const std::string& what) {
  if (!muscle.facts->thermal.reports_temperature) {
    section.fail(what +
                 " the muscle's temperature: use the physical thermal form, or give the reduced "
                 "form's thermal_force.force_per_kelvin");
  }
}

// A heat term's loss into the muscle's heat balance (its fan-in heat_loss).
void connect_heat_loss(SystemBuilder& system, const MuscleAttachment& muscle) {
  system.connect(muscle.muscle + ".heat_loss", muscle.group + ".heat_loss");
}

// A heat loss of the muscle's temperature over its ambient, into its heat balance.
void connect_heat_term(SystemBuilder& system, const Component& term,
                       const MuscleAttachment& muscle) {
  system.connect(term, "temperature", muscle.muscle + ".temperature");
  system.connect(term, "ambient_temperature", muscle.muscle + ".ambient_temperature");
  connect_heat_loss(system, muscle);
}

// A heat term depends on the muscle's temperature, which the reduced form reports only with
// its force_per_kelvin.
void require_heat_terms(const ConfigNode& section, const MuscleAttachment& muscle,
                        const std::string& what) {
  if (!muscle.facts->thermal.takes_heat_terms) {
    section.fail(what +
                 " needs the muscle's temperature: use the physical thermal form, or give the "
                 "reduced form's thermal_force.force_per_kelvin");
  }
}

void attach_maxwell_branch(const ConfigNode& section, const MuscleAttachment& muscle,
                           ScenarioBuilder& build) {
  SystemBuilder& system = build.system();
  connect_deflection_term(system, system.add(MaxwellBranch::from_config(muscle.group, section)),
                          muscle);
}

void attach_free_convection(const ConfigNode& section, const MuscleAttachment& muscle,
                            ScenarioBuilder& build) {
  require_heat_terms(section, muscle, "free convection");
  SystemBuilder& system = build.system();
  connect_heat_term(system, system.add(FreeConvection::from_config(muscle.group, section)), muscle);
}

void attach_thermal_softening(const ConfigNode& section, const MuscleAttachment& muscle,
                              ScenarioBuilder& build) {
  require_temperature(section, muscle, "a temperature-dependent stiffness needs");
  SystemBuilder& system = build.system();
  auto& spring = system.add(ThermalSoftening::from_config(muscle.group, section));
  system.connect(spring, "temperature", muscle.muscle + ".temperature");
  system.connect(spring, "deflection", muscle.muscle + ".deflection");
  connect_force_term(system, muscle);
  // At rest, s(T_0) x at the muscle's starting temperature.
  muscle.facts->rest_force_attached = true;
  const double stiffness_as_built =
      thermal_softening::stiffness(spring.defaults(), muscle.facts->thermal.initial_temperature);
  muscle.facts->rest_forces.push_back(
      [stiffness_as_built](double deflection) { return stiffness_as_built * deflection; });
  const auto starting = muscle.facts->thermal.initial_temperature_in;
  muscle.facts->rest_forces_in.push_back([&spring, starting](const Context& context) -> RestForce {
    const double stiffness =
        thermal_softening::stiffness(spring.parameters_in(context), starting(context));
    return [stiffness](double deflection) { return stiffness * deflection; };
  });
}

void attach_hysteresis(const ConfigNode& section, const MuscleAttachment& muscle,
                       ScenarioBuilder& build) {
  SystemBuilder& system = build.system();
  connect_deflection_term(system, system.add(Hysteresis::from_config(muscle.group, section)),
                          muscle);
}

void attach_nonlinear_stiffness(const ConfigNode& section, const MuscleAttachment& muscle,
                                ScenarioBuilder& build) {
  SystemBuilder& system = build.system();
  auto& knee = system.add(NonlinearStiffness::from_config(muscle.group, section));
  connect_deflection_term(system, knee, muscle);
  // At rest its follower sits at the deflection: F_n(x).
  muscle.facts->rest_force_attached = true;
  const auto defaults = knee.defaults();
  muscle.facts->rest_forces.push_back(
      [defaults](double deflection) { return nonlinear_stiffness::force(defaults, deflection); });
  muscle.facts->rest_forces_in.push_back([&knee](const Context& context) -> RestForce {
    return [p = knee.parameters_in(context)](double deflection) {
      return nonlinear_stiffness::force(p, deflection);
    };
  });
}

void attach_thermal_lag(const ConfigNode& section, const MuscleAttachment& muscle,
                        ScenarioBuilder& build) {
  require_heat_terms(section, muscle, "a thermal lag");
  SystemBuilder& system = build.system();
  auto& lag = system.add(ThermalLag::from_config(muscle.group, section));
  system.share_input(muscle.muscle + ".power", lag, "power");
  system.connect(lag, "temperature", muscle.muscle + ".temperature");
  connect_heat_loss(system, muscle);
}

void attach_heating_lag(const ConfigNode& section, const MuscleAttachment& muscle,
                        ScenarioBuilder& build) {
  require_heat_terms(section, muscle, "a heating lag");
  SystemBuilder& system = build.system();
  auto& lag = system.add(HeatingLag::from_config(muscle.group, section));
  system.share_input(muscle.muscle + ".power", lag, "power");
  connect_heat_loss(system, muscle);
}

void attach_heat_sink(const ConfigNode& section, const MuscleAttachment& muscle,
                      ScenarioBuilder& build) {
  require_heat_terms(section, muscle, "a heat sink");
  SystemBuilder& system = build.system();
  auto& sink = system.add(HeatSink::from_config(muscle.group, section));
  system.connect(sink, "temperature", muscle.muscle + ".temperature");
  connect_heat_loss(system, muscle);
}

void attach_ratchet(const ConfigNode& section, const MuscleAttachment& muscle,
                    ScenarioBuilder& build) {
  require_temperature(section, muscle, "a ratchet is driven by");
  SystemBuilder& system = build.system();
  auto& ratchet = system.add(Ratchet::from_config(muscle.group, section));
  system.connect(ratchet, "temperature", muscle.muscle + ".temperature");
  connect_force_term(system, muscle);
}

void attach_heating_convection(const ConfigNode& section, const MuscleAttachment& muscle,
                               ScenarioBuilder& build) {
  require_heat_terms(section, muscle, "a heating-driven convection");
  SystemBuilder& system = build.system();
  auto& convection = system.add(HeatingConvection::from_config(muscle.group, section));
  system.share_input(muscle.muscle + ".power", convection, "power");
  connect_heat_term(system, convection, muscle);
}

// ---------------------------------------------------------------------------------------------
// How `tcpmsim discover` tries each kind (models/effects/effect_candidates.h). Every member is
// the base model at its starts (zero size); the bounds are in the base model's scales.

using S = CandidateScale;

CandidateKey free_key(std::string key, std::string unit, CandidateValue start, CandidateValue lower,
                      CandidateValue upper) {
  return {std::move(key), std::move(unit), start, lower, upper};
}

CandidateKey fixed_key(std::string key, std::string unit, CandidateValue value) {
  return {std::move(key), std::move(unit), value, std::nullopt, std::nullopt};
}

// A Maxwell branch of zero stiffness whose time constant is free within [low, high].
std::vector<CandidateKey> branch_keys(double stiffness_limit, double start, double low,
                                      double high) {
  return {free_key("stiffness", "N/m", fixed_value(0.0), fixed_value(0.0),
                   scaled(stiffness_limit, S::k2)),
          free_key("time_constant", "s", fixed_value(start), fixed_value(low), fixed_value(high))};
}

const char* const kDrift = "drift; low-frequency residual power";

CandidateDeclaration maxwell_branch_candidates() {
  CandidateFamily slow{"slow_relaxation",
                       0,
                       "a further viscoelastic branch with a long time constant (warm-up)",
                       kDrift,
                       {},
                       {}};
  // A Prony series told apart from viscoelastic_relaxation by its relaxation times: minutes
  // (warm-up) against seconds (the SLS's own order); the ranges meet at 30 s.
  slow.members.push_back(
      {"one Maxwell branch", 1, {branch_keys(3.0, 200.0, 30.0, 3000.0)}, {}, {}});
  slow.members.push_back(
      {"two Maxwell branches (Prony series)",
       2,
       {branch_keys(3.0, 100.0, 30.0, 300.0), branch_keys(3.0, 1000.0, 300.0, 3000.0)},
       {},
       {}});
  CandidateFamily branch{"viscoelastic_relaxation",
                         7,
                         "an SLS branch, for base models that lack one",
                         "residual against dx/dt",
                         {},
                         {{"one Maxwell branch", 1, {branch_keys(5.0, 5.0, 0.05, 30.0)}, {}, {}}}};
  return {{slow, branch}, ""};
}

CandidateDeclaration hysteresis_candidates() {
  // Stop operators weighted by non-negative stiffnesses (zero: no hysteresis): one of free
  // radius (Dahl's element), or a Prandtl-Ishlinskii operator on radii over the measured range.
  CandidateFamily family{
      "hysteresis",
      1,
      "rate-independent hysteresis in the force",
      "residual against the direction of the last motion; loop area flat in frequency",
      {},
      {}};
  family.members.push_back(
      {"one Dahl element, free radius",
       1,
       {{free_key("stiffness", "N/m", fixed_value(0.0), fixed_value(0.0), scaled(50.0, S::k1)),
         free_key("radius", "m", scaled(0.02, S::range), scaled(0.002, S::range),
                  scaled(0.5, S::range))}},
       {},
       {}});
  family.members.push_back(
      {"Prandtl-Ishlinskii operator, 4 radii",
       4,
       {{free_key("stiffness", "N/m", fixed_value(0.0), fixed_value(0.0), scaled(20.0, S::k1))}},
       CandidateGrid{"radius", "m", scaled(0.02, S::range), scaled(0.3, S::range), 4},
       {}});
  return {{family}, ""};
}

// A kind discover tries as one family of one form, its keys in one section.
CandidateDeclaration one_form(CandidateFamily family, std::string member,
                              std::vector<CandidateKey> keys) {
  family.members.push_back({std::move(member), 1, {std::move(keys)}, {}, {}});
  return {{std::move(family)}, ""};
}

// A muscle with the physical thermal form (free convection needs its heat balance) and one
// free_convection entry with `keys`.
std::string free_convection_example(const std::string& keys) {
  return R"(scenario: {name: example, duration: 10 s}
output: {rate: 10 Hz}
muscle:
  thermal: {heat_capacity: 0.3 J/K, conductance: 0.01 W/K, ambient_temperature: 23 degC}
  thermal_force: {form: physical, force_per_kelvin: 0.004 N/K, reference_temperature: 23 degC}
  mechanics: {k1: 10.8e-3 N/mm, k2: 2.7e-3 N/mm, damping: 4.3e-3 N*s/mm, force_offset: 0.1 N}
  resistance: 10 ohm
  inductance: {quantity: measure, lambda_l: 2.81 mm, lambda_x: 28.8 mm, lambda_0: 0.433}
  effects:
    - {type: free_convection, name: still_air, )" +
         keys + R"(}
drive: {mode: power, power: 1 W}
load: {type: deflection, deflection: 20 mm}
)";
}

CandidateDeclaration free_convection_candidates() {
  return one_form(
      {"nonlinear_convection",
       2,
       "heat loss growing faster than linearly with the temperature rise",
       "residual against temperature; against power at steady heating",
       {CandidateNeed::temperature},
       {}},
      "G dT_ref (dT/dT_ref)^n, free exponent",
      {free_key("conductance", "W/K", fixed_value(0.0), fixed_value(0.0),
                scaled(3.0, S::conductance)),
       fixed_key("reference_difference", "K", fixed_value(50.0)),
       free_key("exponent", "1", fixed_value(1.25), fixed_value(1.0), fixed_value(2.0))});
}

// A second thermal node, before the polymer (heating_lag) or beside it (heat_sink): one family
// declared by two kinds, its members tried side by side.
CandidateFamily thermal_lag_family() {
  return {"thermal_lag",
          3,
          "a second thermal node: the heat reaches the polymer late (heater wire, coating) or a "
          "body it touches stores some (clamp, holder)",
          "residual cross-correlated with power at short lags",
          {CandidateNeed::temperature},
          {}};
}

CandidateDeclaration heating_lag_candidates() {
  return one_form(
      thermal_lag_family(), "a share of the power through a first-order lag",
      {free_key("share", "1", fixed_value(0.0), fixed_value(0.0), fixed_value(1.0)),
       free_key("time_constant", "s", fixed_value(2.0), fixed_value(0.1), fixed_value(30.0))});
}

CandidateDeclaration heat_sink_candidates() {
  // A body of time constant 1-100 s that takes up to 5 hA from the polymer while it lags.
  return one_form(
      thermal_lag_family(), "a heat sink beside the polymer, G_s (T - T_s)",
      {free_key("conductance", "W/K", fixed_value(0.0), fixed_value(0.0),
                scaled(5.0, S::conductance)),
       free_key("time_constant", "s", fixed_value(10.0), fixed_value(1.0), fixed_value(100.0))});
}

CandidateDeclaration nonlinear_stiffness_candidates() {
  return one_form(
      {"nonlinear_stiffness",
       4,
       "stiffness that depends on deflection (coil contact, preload knee)",
       "residual against deflection",
       {CandidateNeed::deflection},
       {}},
      "a softplus knee, free sharpness",
      {free_key("stiffness", "N/m", fixed_value(0.0), scaled(-0.9, S::k1), scaled(5.0, S::k1)),
       free_key("knee_deflection", "m", scaled(0.5, S::deflection_sum),
                scaled(1.0, S::deflection_low), scaled(1.0, S::deflection_high)),
       free_key("knee_width", "m", scaled(0.1, S::range), scaled(0.01, S::range),
                scaled(0.5, S::range))});
}

// The thermal_softening keys of a stiffness that changes with the temperature rise dT from the
// ambient: beta dT (+ gamma dT^2), within +-k1 over 50 K (gamma: over 50 K squared).
std::vector<CandidateKey> slope_keys(bool bend) {
  std::vector<CandidateKey> keys = {
      fixed_key("reference_stiffness", "N/m", fixed_value(0.0)),
      fixed_key("temperature_coefficient", "1/K", fixed_value(0.0)),
      fixed_key("reference_temperature", "K", scaled(1.0, S::ambient)),
      free_key("stiffness_slope", "N/(m*K)", fixed_value(0.0), scaled(-0.02, S::k1),
               scaled(0.02, S::k1))};
  if (bend) {
    keys.push_back(free_key("stiffness_curvature", "N/(m*K^2)", fixed_value(0.0),
                            scaled(-4e-4, S::k1), scaled(4e-4, S::k1)));
  }
  return keys;
}

CandidateDeclaration thermal_softening_candidates() {
  // The muscle's stiffness changing linearly with temperature, either sign, from zero: a
  // parallel spring of zero size (the floored s_ref form) could only stiffen from there.
  return {{{"temperature_dependent_stiffness",
            5,
            "stiffness that changes with temperature",
            "residual against temperature times deflection",
            {CandidateNeed::temperature},
            {{"k1 + beta (T - T_ref), free slope", 1, {slope_keys(false)}, {}, {}},
             {"k1 + beta dT + gamma dT^2, a bend (a transition)", 2, {slope_keys(true)}, {}, {}}}}},
          ""};
}

CandidateDeclaration ratchet_candidates() {
  // An irreversible loss of force above a threshold temperature, up to k1 x range per 1000 K s.
  return one_form({"ratchet",
                   8,
                   "the rest length creeps irreversibly with each heating cycle",
                   "drift that steps down with each heating; residual against the heat received",
                   {CandidateNeed::temperature},
                   {}},
                  "dF/dt = -g max(0, T - T_th), kept on cooling",
                  {free_key("rate", "N/(K*s)", fixed_value(0.0), fixed_value(0.0),
                            scaled(1.0, S::k1_range, 0.0, 1000.0)),
                   free_key("threshold", "K", scaled(1.0, S::warm), scaled(1.0, S::ambient),
                            scaled(1.0, S::ambient, 100.0))});
}

CandidateDeclaration heating_convection_candidates() {
  CandidateFamily family{
      "heating_dependent_convection",
      9,
      "the heat-transfer coefficient rises while the heating runs (a fan or heat gun)",
      "residual against power times the temperature rise",
      {CandidateNeed::temperature, CandidateNeed::power},
      {}};
  const CandidateKey conductance = free_key("conductance", "W/K", fixed_value(0.0),
                                            fixed_value(0.0), scaled(3.0, S::conductance));
  const CandidateKey lag =
      free_key("time_constant", "s", fixed_value(1.0), fixed_value(0.05), fixed_value(60.0));
  family.members.push_back(
      {"Q = G_P (P_b / P_peak) (T - T_amb), P_b lagging P",
       1,
       {{conductance, fixed_key("reference_power", "W", scaled(1.0, S::power_peak)), lag}},
       {},
       {}});
  // A fan switched on above a power (a relay): the switch's place and width within the
  // measured power's range.
  family.members.push_back({"Q = G_P s(P_b) (T - T_amb), a switch at a free power",
                            2,
                            {{conductance,
                              free_key("switch_power", "W", scaled(0.5, S::power_peak),
                                       scaled(0.05, S::power_peak), scaled(0.95, S::power_peak)),
                              free_key("switch_width", "W", scaled(0.1, S::power_peak),
                                       scaled(0.02, S::power_peak), scaled(0.5, S::power_peak)),
                              lag}},
                            {},
                            {}});
  return {{family}, ""};
}

CandidateDeclaration thermal_lag_exclusion() {
  return {{},
          "its family, thermal_lag, is tried as heating_lag and heat_sink: a wire node's capacity "
          "cannot reach zero (the base model) without a stiff limit, a lagged share of the power "
          "can"};
}

}  // namespace

void register_effect_kinds(KindRegistry& kinds) {
  kinds.add({kEffectCategory,
             "maxwell_branch",
             "a spring in series with a dashpot, in parallel with the SLS: one more relaxation "
             "time c_b/k_b (generalized Maxwell solid); give damping c_b or time_constant",
             {{example_muscle_scenario("  effects:\n    - {type: maxwell_branch, name: slow, "
                                       "stiffness: 1.5 mN/mm, damping: 30 mN*s/mm}\n",
                                       ""),
               "muscle.effects[0]"},
              {example_muscle_scenario("  effects:\n    - {type: maxwell_branch, name: slow, "
                                       "stiffness: 1.5 mN/mm, time_constant: 20 s}\n",
                                       ""),
               "muscle.effects[0]"}},
             EffectBuilder(attach_maxwell_branch),
             maxwell_branch_candidates()});
  kinds.add({kEffectCategory,
             "free_convection",
             "laminar free convection, Q = G dT_ref (dT/dT_ref)^(5/4), or ^n with `exponent` n "
             "from 1 to 2, in the heat balance of the thermal node's physical form",
             {{free_convection_example("conductance: 0.01 W/K, reference_difference: 50 K"),
               "muscle.effects[0]"},
              {free_convection_example(
                   "conductance: 0.01 W/K, reference_difference: 50 K, exponent: 1.4"),
               "muscle.effects[0]"}},
             EffectBuilder(attach_free_convection),
             free_convection_candidates()});
  kinds.add({kEffectCategory,
             "thermal_softening",
             "a spring in parallel with the SLS whose stiffness falls with temperature, "
             "s = max(0, s_ref (1 + alpha (T - T_ref))) + beta (T - T_ref) + gamma (T - T_ref)^2: "
             "a heated polymer softens (beta, stiffness_slope, and gamma, stiffness_curvature, "
             "optional: the muscle's own stiffness, either sign, and its bend)",
             {{example_muscle_scenario(
                   "  effects:\n    - {type: thermal_softening, name: softening, "
                   "reference_stiffness: 5 mN/mm, temperature_coefficient: -0.01 1/K, "
                   "reference_temperature: 23 degC}\n",
                   ""),
               "muscle.effects[0]"},
              {example_muscle_scenario(
                   "  effects:\n    - {type: thermal_softening, name: softening, "
                   "reference_stiffness: 0 N/m, temperature_coefficient: 0 1/K, "
                   "reference_temperature: 23 degC, stiffness_slope: -0.05 mN/(mm*K), "
                   "stiffness_curvature: 5e-4 mN/(mm*K^2)}\n",
                   ""),
               "muscle.effects[0]"}},
             EffectBuilder(attach_thermal_softening),
             thermal_softening_candidates()});
  kinds.add({kEffectCategory,
             "hysteresis",
             "rate-independent hysteresis in the force (Dahl): dz/dt = k_h (v - |v| z/F_h), "
             "saturating at +-F_h, in parallel with the SLS; given by its radius r = F_h/k_h, a "
             "stop operator weighted by k_h (several on a grid of radii: Prandtl-Ishlinskii)",
             {{example_muscle_scenario("  effects:\n    - {type: hysteresis, name: friction, "
                                       "stiffness: 20 mN/mm, force: 5 mN}\n",
                                       ""),
               "muscle.effects[0]"},
              {example_muscle_scenario("  effects:\n    - {type: hysteresis, name: play_1, "
                                       "stiffness: 2 mN/mm, radius: 0.5 mm}\n    - {type: "
                                       "hysteresis, name: play_2, stiffness: 1 mN/mm, radius: "
                                       "3 mm}\n",
                                       ""),
               "muscle.effects[0]"}},
             EffectBuilder(attach_hysteresis),
             hysteresis_candidates()});
  kinds.add({kEffectCategory,
             "nonlinear_stiffness",
             "a stiffness that engages past a knee deflection (coil contact): F = k_n w "
             "softplus((x - x_k)/w), in parallel with the SLS",
             {{example_muscle_scenario("  effects:\n    - {type: nonlinear_stiffness, name: knee, "
                                       "stiffness: 10 mN/mm, knee_deflection: 25 mm, "
                                       "knee_width: 1 mm}\n",
                                       ""),
               "muscle.effects[0]"}},
             EffectBuilder(attach_nonlinear_stiffness),
             nonlinear_stiffness_candidates()});
  kinds.add({kEffectCategory,
             "thermal_lag",
             "the heater wire as a second thermal node: C_w dT_w/dt = P - G_w (T_w - T), the "
             "polymer heated by G_w (T_w - T) instead of P",
             {{example_muscle_scenario("  effects:\n    - {type: thermal_lag, name: wire, "
                                       "heat_capacity: 0.05 J/K, conductance: 0.5 W/K}\n",
                                       ""),
               "muscle.effects[0]"}},
             EffectBuilder(attach_thermal_lag),
             thermal_lag_exclusion()});
  kinds.add({kEffectCategory,
             "heating_lag",
             "a share a of the heating power reaches the polymer through a first-order lag: "
             "tau dP_l/dt = P - P_l, the polymer heated by (1 - a) P + a P_l",
             {{example_muscle_scenario("  effects:\n    - {type: heating_lag, name: wire, "
                                       "share: 0.5, time_constant: 2 s}\n",
                                       ""),
               "muscle.effects[0]"}},
             EffectBuilder(attach_heating_lag),
             heating_lag_candidates()});
  kinds.add({kEffectCategory,
             "heat_sink",
             "a body beside the polymer that stores heat (a clamp, a holder): tau_s dT_s/dt = "
             "T - T_s, the polymer losing G_s (T - T_s) to it; give time_constant tau_s or "
             "heat_capacity C_s = G_s tau_s",
             {{example_muscle_scenario("  effects:\n    - {type: heat_sink, name: clamp, "
                                       "conductance: 0.02 W/K, time_constant: 15 s}\n",
                                       ""),
               "muscle.effects[0]"},
              {example_muscle_scenario("  effects:\n    - {type: heat_sink, name: clamp, "
                                       "conductance: 0.02 W/K, heat_capacity: 0.3 J/K}\n",
                                       ""),
               "muscle.effects[0]"}},
             EffectBuilder(attach_heat_sink),
             heat_sink_candidates()});
  kinds.add({kEffectCategory,
             "ratchet",
             "an irreversible loss of force as the rest length creeps above a threshold "
             "temperature: dF_r/dt = -g max(0, T - T_th), kept when the muscle cools",
             {{example_muscle_scenario("  effects:\n    - {type: ratchet, name: creep, "
                                       "rate: 2e-6 N/(K*s), threshold: 40 degC}\n",
                                       ""),
               "muscle.effects[0]"}},
             EffectBuilder(attach_ratchet),
             ratchet_candidates()});
  kinds.add({kEffectCategory,
             "heating_convection",
             "a heat-transfer coefficient that rises with the heating input (a fan or heat "
             "gun running with the heater): Q = G_P (P_b / P_ref) (T - T_amb), or switched on "
             "above a power, Q = G_P s(P_b) (T - T_amb) with s(P) = (sigma(P) - sigma(0)) / (1 - "
             "sigma(0)), sigma(P) = 1 / (1 + exp(-(P - P_on) / w)): off at rest; the boost P_b "
             "following the input P with time constant tau (0: at once)",
             {{example_muscle_scenario("  effects:\n    - {type: heating_convection, name: fan, "
                                       "conductance: 0.02 W/K, reference_power: 3 W}\n",
                                       ""),
               "muscle.effects[0]"},
              {example_muscle_scenario("  effects:\n    - {type: heating_convection, name: fan, "
                                       "conductance: 0.02 W/K, switch_power: 1.6 W, "
                                       "switch_width: 0.15 W, time_constant: 2 s}\n",
                                       ""),
               "muscle.effects[0]"}},
             EffectBuilder(attach_heating_convection),
             heating_convection_candidates()});
}

}  // namespace tcpmsim
