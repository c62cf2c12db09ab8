#include "identification/effect_catalogue.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
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

// Builds one candidate: an effect section appended to the muscle's effects, its fitted keys.
class CandidateBuilder {
 public:
  CandidateBuilder(const BaseModel& base, std::string name, std::string description,
                   std::string signature)
      : base_(base) {
    candidate_.name = std::move(name);
    candidate_.description = std::move(description);
    candidate_.signature = std::move(signature);
  }
  // The effect section's kind.
  CandidateBuilder& attach(const std::string& kind) {
    section_["type"] = kind;
    section_["name"] = candidate_.name;
    return *this;
  }
  // A key at a fixed value.
  CandidateBuilder& fixed(const std::string& key, double value, const std::string& unit) {
    section_[key] = quantity(value, unit);
    return *this;
  }
  // A key the refit frees within [lower, upper], starting at `initial`.
  CandidateBuilder& free(const std::string& key, double initial, double lower, double upper,
                         const std::string& unit) {
    fixed(key, initial, unit);
    const auto index = base_.effects ? base_.effects.size() : 0;
    candidate_.parameters.push_back(
        {base_.muscle + ".effects[" + std::to_string(index) + "]." + key, unit, lower, upper});
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
  // A parameter of the base model the refit frees.
  CandidateBuilder& free_base(const std::string& path, double lower, double upper,
                              const std::string& unit) {
    candidate_.parameters.push_back({path, unit, lower, upper});
    return *this;
  }
  EffectCandidate build() {
    if (section_.size() > 0) {
      YAML::Node effects =
          base_.effects ? YAML::Clone(base_.effects) : YAML::Node(YAML::NodeType::Sequence);
      effects.push_back(section_);
      candidate_.overrides.push_back(base_.muscle + ".effects=" + flow_text(effects));
    }
    return candidate_;
  }

 private:
  const BaseModel& base_;
  EffectCandidate candidate_;
  YAML::Node section_;
};

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
  static const std::vector<std::string> names = {
      "slow_relaxation",        "hysteresis",
      "nonlinear_convection",   "thermal_lag",
      "nonlinear_stiffness",    "temperature_dependent_stiffness",
      "inductance_temperature", "viscoelastic_relaxation"};
  return names;
}

Candidates effect_candidates(const Scenario& scenario, const Context& fitted,
                             const MeasuredData& data, const std::vector<std::string>& outputs) {
  const BaseModel base = read_base(scenario, fitted, data, outputs);
  Candidates result;
  const auto skip = [&](const std::string& name, const std::string& reason) {
    result.skipped.push_back({name, reason});
  };
  const double k1 = base.k1, k2 = base.k2, c = base.heat_capacity, ha = base.conductance;
  // A further viscoelastic branch, told apart by its relaxation time: minutes (warm-up) for
  // slow_relaxation, seconds (the SLS's own order) for viscoelastic_relaxation; the two ranges
  // meet at 30 s and do not overlap.
  result.candidates.push_back(
      CandidateBuilder(base, "slow_relaxation",
                       "a second viscoelastic branch with a long time constant (warm-up)",
                       "drift; low-frequency residual power")
          .attach("maxwell_branch")
          .free("stiffness", 0.02 * k2, 0.005 * k2, 3.0 * k2, "N/m")
          .free("time_constant", 200.0, 30.0, 3000.0, "s")
          .build());
  result.candidates.push_back(
      CandidateBuilder(
          base, "hysteresis", "rate-independent hysteresis in the force (Dahl)",
          "residual against the direction of the last motion; loop area flat in frequency")
          .attach("hysteresis")
          .free("stiffness", k1, 0.05 * k1, 50.0 * k1, "N/m")
          .free("force", 2e-4, 5e-5, 5e-2, "N")
          .build());
  if (!base.temperature || !(c > 0.0)) {
    for (const char* name :
         {"nonlinear_convection", "thermal_lag", "temperature_dependent_stiffness"}) {
      skip(name,
           "the muscle reports no temperature (give the reduced form's force_per_kelvin, or use "
           "the physical form)");
    }
  } else {
    result.candidates.push_back(
        CandidateBuilder(base, "nonlinear_convection",
                         "heat loss growing faster than linearly with the temperature rise",
                         "residual against temperature; against power at steady heating")
            .attach("free_convection")
            .free("conductance", 0.01 * ha, 0.001 * ha, 3.0 * ha, "W/K")
            .fixed("reference_difference", 50.0, "K")
            .build());
    result.candidates.push_back(
        CandidateBuilder(base, "thermal_lag", "heater wire and polymer as two thermal nodes",
                         "residual cross-correlated with power at short lags")
            .attach("thermal_lag")
            // Starting as a wire that follows at once (tau_w = C_w / G_w of 1e-4 C / hA), so that
            // the augmented model starts where the base model ended.
            .free("heat_capacity", 0.01 * c, 0.001 * c, c, "J/K")
            .free("conductance", 100.0 * ha, 0.5 * ha, 1000.0 * ha, "W/K")
            .build());
  }
  if (base.deflection) {
    const auto [low, high] = *base.deflection;
    const double range = high - low;
    result.candidates.push_back(
        CandidateBuilder(base, "nonlinear_stiffness",
                         "stiffness that depends on deflection (coil contact, preload knee)",
                         "residual against deflection")
            .attach("nonlinear_stiffness")
            .free("stiffness", 0.02 * k1, -0.9 * k1, 5.0 * k1, "N/m")
            .free("knee_deflection", 0.5 * (low + high), low, high, "m")
            .free("knee_width", 0.1 * range, 0.01 * range, 0.5 * range, "m")
            .build());
  } else {
    skip("nonlinear_stiffness", "the measurement has no deflection channel to place a knee in");
  }
  if (base.temperature && c > 0.0) {
    result.candidates.push_back(CandidateBuilder(base, "temperature_dependent_stiffness",
                                                 "stiffness that changes with temperature",
                                                 "residual against temperature times deflection")
                                    .attach("thermal_softening")
                                    .fixed("reference_stiffness", 0.5 * k1, "N/m")
                                    .fixed("reference_temperature", base.ambient, "K")
                                    .free("temperature_coefficient", 0.0, -0.03, 0.03, "1/K")
                                    .build());
  }
  if (!base.coil_output) {
    skip("inductance_temperature", "no output of the coil (inductance or L*) is compared");
  } else if (!base.temperature || !base.inductance ||
             !scenario.system->parameter_index(base.lambda_path)) {
    skip("inductance_temperature", "the muscle's coil has no temperature term to free");
  } else {
    // The impedance law's own lambda_T (T - T_ref) term, zero in the base model: a coil built
    // without it has no temperature input, so the candidate starts it off zero.
    const double scale = base.lambda_scale > 0.0 ? base.lambda_scale : 1.0;
    const auto index = *scenario.system->parameter_index(base.lambda_path);
    const std::string unit =
        scenario.system->parameters()[static_cast<std::size_t>(index)].declaration.unit;
    result.candidates.push_back(
        CandidateBuilder(base, "inductance_temperature",
                         "the inductance measure depends on temperature",
                         "L* residual against temperature")
            .set_in_section("inductance", base.inductance, "lambda_T", 1e-5 * scale, unit)
            .free_base(base.lambda_path, -0.01 * scale, 0.01 * scale, unit)
            .build());
  }
  result.candidates.push_back(CandidateBuilder(base, "viscoelastic_relaxation",
                                               "an SLS branch, for base models that lack one",
                                               "residual against dx/dt")
                                  .attach("maxwell_branch")
                                  .free("stiffness", 0.02 * k2, 0.005 * k2, 5.0 * k2, "N/m")
                                  .free("time_constant", 5.0, 0.05, 30.0, "s")
                                  .build());
  return result;
}

}  // namespace tcpmsim::fit
