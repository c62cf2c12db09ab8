#include "identification/effect_catalogue.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

#include "sim/config/config_error.h"
#include "sim/value_check.h"

namespace tcpmsim::fit {

namespace {

// The base model as the catalogue sees it: its muscle, what it publishes, and its scales (SI).
struct BaseModel {
  std::string muscle;  // the instance ("muscle")
  bool temperature = false;
  bool coil_output = false;  // an inductance (or L*) output is compared
  double k1 = 0.0, k2 = 0.0;
  double heat_capacity = 0.0, conductance = 0.0, ambient = 0.0;  // C, hA, T_amb
  std::optional<std::pair<double, double>> deflection;           // measured range
  double power_peak = 0.0;                                       // the measured power's largest
  std::string lambda_path;                                       // <muscle>.inductance.lambda_T
  double lambda_scale = 0.0;                                     // |lambda_0|
  YAML::Node effects;                                            // the muscle's own, if any
  YAML::Node inductance;                                         // its coil law's section
};

std::optional<double> parameter(const Context& context, const std::string& path) {
  if (!context.system().parameter_index(path)) return std::nullopt;
  return context.parameter(path);
}

BaseModel read_base(const Scenario& scenario, const Context& fitted, const MeasuredData& data,
                    const std::vector<std::string>& outputs) {
  const System& system = *scenario.system;
  BaseModel base;
  base.muscle = only_muscle(system);
  const std::string& m = base.muscle;
  base.temperature = system.signal_index(m + ".temperature") >= 0;
  for (const auto& output : outputs)
    base.coil_output = base.coil_output || output == m + ".inductance" ||
                       output == m + ".inductance_measure" ||
                       output.find("decay_time") != std::string::npos;
  base.k1 = fitted.parameter(m + ".mechanics.k1");
  base.k2 = fitted.parameter(m + ".mechanics.k2");
  if (auto capacity = parameter(fitted, m + ".thermal.heat_capacity")) {
    base.heat_capacity = *capacity;
    base.conductance = fitted.parameter(m + ".thermal.conductance");
    base.ambient = parameter(fitted, m + ".thermal.ambient_temperature").value_or(293.15);
  } else if (auto phi = parameter(fitted, m + ".thermal_force.force_per_kelvin")) {
    // (7.1)'s kappa_P = phi_T / C and kappa_c = hA / C.
    base.heat_capacity = *phi / fitted.parameter(m + ".thermal_force.kappa_P");
    base.conductance = fitted.parameter(m + ".thermal_force.kappa_c") * base.heat_capacity;
    base.ambient = fitted.parameter(m + ".thermal_force.ambient_temperature");
  }
  if (const auto* channel = data.find("deflection")) {
    const auto [low, high] = std::minmax_element(channel->values.begin(), channel->values.end());
    if (*high > *low) base.deflection = std::make_pair(*low, *high);
  }
  if (const auto* channel = data.find("power"); channel && !channel->values.empty())
    base.power_peak = *std::max_element(channel->values.begin(), channel->values.end());
  base.lambda_path = m + ".inductance.lambda_T";
  if (auto lambda_0 = parameter(fitted, m + ".inductance.lambda_0"))
    base.lambda_scale = std::abs(*lambda_0);
  const YAML::Node resolved = YAML::Load(scenario.resolved_yaml);
  if (resolved[m] && resolved[m]["effects"]) base.effects = YAML::Clone(resolved[m]["effects"]);
  if (resolved[m] && resolved[m]["inductance"])
    base.inductance = YAML::Clone(resolved[m]["inductance"]);
  return base;
}

std::string quantity(double value, const std::string& unit) {
  return number_text(value, 17) + (unit == "1" ? "" : " " + unit);
}

std::string flow_text(const YAML::Node& node) {
  YAML::Emitter flow;
  flow.SetMapFormat(YAML::Flow);
  flow.SetSeqFormat(YAML::Flow);
  flow << node;
  return flow.c_str();
}

// Builds one candidate: effect sections appended to the muscle's effects, its fitted keys.
class CandidateBuilder {
 public:
  CandidateBuilder(const BaseModel& base, std::string name, std::string member, int order,
                   std::string description, std::string signature)
      : base_(base) {
    candidate_.name = std::move(name);
    candidate_.member = std::move(member);
    candidate_.order = order;
    candidate_.description = std::move(description);
    candidate_.signature = std::move(signature);
  }
  // A new effect section of this kind; the keys that follow go into it.
  CandidateBuilder& attach(const std::string& kind) {
    sections_.emplace_back();
    sections_.back()["type"] = kind;
    sections_.back()["name"] =
        candidate_.name + (sections_.size() > 1 ? "_" + std::to_string(sections_.size()) : "");
    return *this;
  }
  // A key at a fixed value.
  CandidateBuilder& fixed(const std::string& key, double value, const std::string& unit) {
    sections_.back()[key] = quantity(value, unit);
    return *this;
  }
  // A key the refit frees within [lower, upper]; the scenario and the refit's first start hold
  // it at `nested`, where the member is the base model.
  CandidateBuilder& free(const std::string& key, double nested, double lower, double upper,
                         const std::string& unit) {
    fixed(key, nested, unit);
    const auto index = (base_.effects ? base_.effects.size() : 0) + sections_.size() - 1;
    candidate_.parameters.push_back(
        {base_.muscle + ".effects[" + std::to_string(index) + "]." + key, unit, lower, upper});
    candidate_.nested.push_back(nested);
    return *this;
  }
  // A key of the muscle's section `section` set to `value` in the scenario the candidate builds
  // (not in a run's context: a term the base model lacks is assembled only when given).
  CandidateBuilder& set_in_section(const std::string& section, const YAML::Node& resolved,
                                   const std::string& key, double value, const std::string& unit) {
    YAML::Node changed = YAML::Clone(resolved);
    changed[key] = quantity(value, unit);
    // A temperature term is referred to a temperature: the ambient, unless the section has one.
    if (!changed["reference_temperature"])
      changed["reference_temperature"] = quantity(base_.ambient, "K");
    candidate_.overrides.push_back(base_.muscle + "." + section + "=" + flow_text(changed));
    return *this;
  }
  // A parameter of the base model the refit frees, starting at `nested`.
  CandidateBuilder& free_base(const std::string& path, double nested, double lower, double upper,
                              const std::string& unit) {
    candidate_.parameters.push_back({path, unit, lower, upper});
    candidate_.nested.push_back(nested);
    return *this;
  }
  EffectCandidate build() {
    if (!sections_.empty()) {
      YAML::Node effects =
          base_.effects ? YAML::Clone(base_.effects) : YAML::Node(YAML::NodeType::Sequence);
      for (const auto& section : sections_) effects.push_back(section);
      candidate_.overrides.push_back(base_.muscle + ".effects=" + flow_text(effects));
    }
    return candidate_;
  }

 private:
  const BaseModel& base_;
  EffectCandidate candidate_;
  std::vector<YAML::Node> sections_;
};

// n values from `low` to `high`, evenly spaced in their logarithm.
std::vector<double> log_grid(double low, double high, int n) {
  std::vector<double> grid;
  for (int i = 0; i < n; ++i)
    grid.push_back(low * std::pow(high / low, n > 1 ? static_cast<double>(i) / (n - 1) : 0.0));
  return grid;
}

}  // namespace

std::string only_muscle(const System& system) {
  std::string found;
  for (const auto& component : system.components()) {
    if (component->kind() != "sls_mechanics") continue;
    if (!found.empty())
      throw UsageError("discover needs a model of one muscle; this one has several");
    found = component->group();
  }
  if (found.empty()) throw UsageError("discover needs a model with a muscle");
  return found;
}

const std::vector<std::string>& effect_names() {
  static const std::vector<std::string> names = {"slow_relaxation",
                                                 "hysteresis",
                                                 "nonlinear_convection",
                                                 "thermal_lag",
                                                 "nonlinear_stiffness",
                                                 "temperature_dependent_stiffness",
                                                 "inductance_temperature",
                                                 "viscoelastic_relaxation",
                                                 "ratchet",
                                                 "heating_dependent_convection"};
  return names;
}

Candidates effect_candidates(const Scenario& scenario, const Context& fitted,
                             const MeasuredData& data, const std::vector<std::string>& outputs) {
  const BaseModel base = read_base(scenario, fitted, data, outputs);
  Candidates result;
  const auto skip = [&](const std::string& name, const std::string& reason) {
    result.skipped.push_back({name, reason});
  };
  const auto add = [&](CandidateBuilder& builder) { result.candidates.push_back(builder.build()); };
  const double k1 = base.k1, k2 = base.k2, c = base.heat_capacity, ha = base.conductance;
  // The measured deflection range scales hysteresis radii and knees (2 cm without one).
  const double range = base.deflection ? base.deflection->second - base.deflection->first : 0.02;

  // Further viscoelastic branches (a Prony series), told apart by their relaxation times:
  // minutes (warm-up) for slow_relaxation, seconds (the SLS's own order) for
  // viscoelastic_relaxation; the ranges meet at 30 s and do not overlap. Zero stiffness: none.
  const std::string slow = "a further viscoelastic branch with a long time constant (warm-up)";
  const std::string drift = "drift; low-frequency residual power";
  CandidateBuilder one_slow(base, "slow_relaxation", "one Maxwell branch", 1, slow, drift);
  one_slow.attach("maxwell_branch")
      .free("stiffness", 0.0, 0.0, 3.0 * k2, "N/m")
      .free("time_constant", 200.0, 30.0, 3000.0, "s");
  add(one_slow);
  CandidateBuilder two_slow(base, "slow_relaxation", "two Maxwell branches (Prony series)", 2, slow,
                            drift);
  two_slow.attach("maxwell_branch")
      .free("stiffness", 0.0, 0.0, 3.0 * k2, "N/m")
      .free("time_constant", 100.0, 30.0, 300.0, "s")
      .attach("maxwell_branch")
      .free("stiffness", 0.0, 0.0, 3.0 * k2, "N/m")
      .free("time_constant", 1000.0, 300.0, 3000.0, "s");
  add(two_slow);

  // Rate-independent hysteresis: stop operators weighted by non-negative stiffnesses (zero: no
  // hysteresis), one with a free radius (Dahl's element) or a Prandtl-Ishlinskii operator on a
  // grid of radii over the measured range.
  const std::string hysteresis = "rate-independent hysteresis in the force";
  const std::string direction =
      "residual against the direction of the last motion; loop area flat in frequency";
  CandidateBuilder dahl(base, "hysteresis", "one Dahl element, free radius", 1, hysteresis,
                        direction);
  dahl.attach("hysteresis")
      .free("stiffness", 0.0, 0.0, 50.0 * k1, "N/m")
      .free("radius", 0.02 * range, 0.002 * range, 0.5 * range, "m");
  add(dahl);
  const auto radii = log_grid(0.02 * range, 0.3 * range, 4);
  CandidateBuilder play(base, "hysteresis", "Prandtl-Ishlinskii operator, 4 radii", 4, hysteresis,
                        direction);
  for (const double radius : radii)
    play.attach("hysteresis")
        .fixed("radius", radius, "m")
        .free("stiffness", 0.0, 0.0, 20.0 * k1, "N/m");
  add(play);

  if (!base.temperature || !(c > 0.0)) {
    for (const char* name :
         {"nonlinear_convection", "thermal_lag", "temperature_dependent_stiffness", "ratchet",
          "heating_dependent_convection"}) {
      skip(name,
           "the muscle reports no temperature (give the reduced form's force_per_kelvin, or use "
           "the physical form)");
    }
  } else {
    CandidateBuilder convection(base, "nonlinear_convection",
                                "G dT_ref (dT/dT_ref)^n, free exponent", 1,
                                "heat loss growing faster than linearly with the temperature rise",
                                "residual against temperature; against power at steady heating");
    convection.attach("free_convection")
        .free("conductance", 0.0, 0.0, 3.0 * ha, "W/K")
        .fixed("reference_difference", 50.0, "K")
        .free("exponent", 1.25, 1.0, 2.0, "1");
    add(convection);
    CandidateBuilder lag(base, "thermal_lag", "a share of the power through a first-order lag", 1,
                         "the heat reaches the polymer late (heater wire, coating)",
                         "residual cross-correlated with power at short lags");
    lag.attach("heating_lag")
        .free("share", 0.0, 0.0, 1.0, "1")
        .free("time_constant", 2.0, 0.1, 30.0, "s");
    add(lag);
    // An irreversible loss of force above a threshold temperature, up to some k1 x range per
    // 1000 K s.
    CandidateBuilder ratchet(base, "ratchet", "dF/dt = -g max(0, T - T_th), kept on cooling", 1,
                             "the rest length creeps irreversibly with each heating cycle",
                             "drift that steps down with each heating; residual against the "
                             "heat received");
    ratchet.attach("ratchet")
        .free("rate", 0.0, 0.0, k1 * range / 1000.0, "N/(K*s)")
        .free("threshold", base.ambient + 10.0, base.ambient, base.ambient + 100.0, "K");
    add(ratchet);
    if (base.power_peak > 0.0) {
      CandidateBuilder fan(base, "heating_dependent_convection",
                           "Q = G_P (P_b / P_peak) (T - T_amb), P_b lagging P", 1,
                           "the heat-transfer coefficient rises while the heating runs (a fan "
                           "or heat gun)",
                           "residual against power times the temperature rise");
      fan.attach("heating_convection")
          .free("conductance", 0.0, 0.0, 3.0 * ha, "W/K")
          .fixed("reference_power", base.power_peak, "W")
          .free("time_constant", 1.0, 0.05, 60.0, "s");
      add(fan);
    } else {
      skip("heating_dependent_convection", "the measurement has no power channel");
    }
  }
  if (base.deflection) {
    const auto [low, high] = *base.deflection;
    CandidateBuilder knee(base, "nonlinear_stiffness", "a softplus knee, free sharpness", 1,
                          "stiffness that depends on deflection (coil contact, preload knee)",
                          "residual against deflection");
    knee.attach("nonlinear_stiffness")
        .free("stiffness", 0.0, -0.9 * k1, 5.0 * k1, "N/m")
        .free("knee_deflection", 0.5 * (low + high), low, high, "m")
        .free("knee_width", 0.1 * range, 0.01 * range, 0.5 * range, "m");
    add(knee);
  } else {
    skip("nonlinear_stiffness", "the measurement has no deflection channel to place a knee in");
  }
  if (base.temperature && c > 0.0) {
    CandidateBuilder softening(
        base, "temperature_dependent_stiffness", "s_ref (1 + alpha (T - T_ref)) in parallel", 1,
        "stiffness that changes with temperature", "residual against temperature times deflection");
    softening.attach("thermal_softening")
        .free("reference_stiffness", 0.0, 0.0, k1, "N/m")
        .free("temperature_coefficient", 0.0, -0.03, 0.03, "1/K")
        .fixed("reference_temperature", base.ambient, "K");
    add(softening);
  }
  if (!base.coil_output) {
    skip("inductance_temperature", "no output of the coil (inductance or L*) is compared");
  } else if (!base.temperature || !base.inductance ||
             !scenario.system->parameter_index(base.lambda_path)) {
    skip("inductance_temperature", "the muscle's coil has no temperature term to free");
  } else {
    // The impedance law's own lambda_T (T - T_ref) term, zero in the base model: a coil built
    // without it has no temperature input, so the scenario gives it a value and the refit starts
    // it at zero.
    const double scale = base.lambda_scale > 0.0 ? base.lambda_scale : 1.0;
    const auto index = *scenario.system->parameter_index(base.lambda_path);
    const std::string unit =
        scenario.system->parameters()[static_cast<std::size_t>(index)].declaration.unit;
    CandidateBuilder coil(base, "inductance_temperature", "lambda_T (T - T_ref)", 1,
                          "the inductance measure depends on temperature",
                          "L* residual against temperature");
    coil.set_in_section("inductance", base.inductance, "lambda_T", 1e-5 * scale, unit)
        .free_base(base.lambda_path, 0.0, -0.01 * scale, 0.01 * scale, unit);
    add(coil);
  }
  CandidateBuilder branch(base, "viscoelastic_relaxation", "one Maxwell branch", 1,
                          "an SLS branch, for base models that lack one", "residual against dx/dt");
  branch.attach("maxwell_branch")
      .free("stiffness", 0.0, 0.0, 5.0 * k2, "N/m")
      .free("time_constant", 5.0, 0.05, 30.0, "s");
  add(branch);
  return result;
}

}  // namespace tcpmsim::fit
