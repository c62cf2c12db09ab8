#include "identification/effect_catalogue.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

#include "kinds/standard_kinds.h"
#include "models/effects/effect_candidates.h"
#include "models/muscle.h"
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
  double temperature_peak = 0.0;                                 // the model's warmest, or 0
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
                    const std::vector<std::string>& outputs, const CatalogueContext& context) {
  const MeasuredRoles& roles = context.roles;
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
  if (const auto* channel = data.find(roles.deflection)) {
    const auto [low, high] = std::minmax_element(channel->values.begin(), channel->values.end());
    if (*high > *low) base.deflection = std::make_pair(*low, *high);
  }
  if (const auto* channel = data.find(roles.power); channel && !channel->values.empty())
    base.power_peak = *std::max_element(channel->values.begin(), channel->values.end());
  base.temperature_peak = context.temperature_peak;
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
  // A new effect section of this kind, named after the family (its second section `_2`, and so
  // on), or the first such name no effect holds yet: a model from an earlier discover may carry
  // the family's effect already. The keys that follow go into it.
  CandidateBuilder& attach(const std::string& kind) {
    std::string name = candidate_.name;
    for (int n = 2; named(name); ++n) name = candidate_.name + "_" + std::to_string(n);
    sections_.emplace_back();
    sections_.back()["type"] = kind;
    sections_.back()["name"] = name;
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
  // Whether one of the base model's effects or of the sections so far is called `name` (an effect
  // without a `name` is called after its type).
  bool named(const std::string& name) const {
    const auto called = [&](const YAML::Node& section) {
      const YAML::Node given = section["name"];
      return (given ? given.as<std::string>() : section["type"].as<std::string>("")) == name;
    };
    if (base_.effects)
      for (const auto& section : base_.effects)
        if (called(section)) return true;
    return std::any_of(sections_.begin(), sections_.end(), called);
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

namespace {

// Every family any kind declares, with the kind that builds its sections, in catalogue order.
struct DeclaredFamily {
  const CandidateFamily* family;
  std::string kind;  // the effect kind its sections are of ("" for a law term)
};

std::vector<DeclaredFamily> declared_families(const KindRegistry& kinds,
                                              std::vector<CandidateDeclaration>& storage) {
  std::vector<std::pair<std::string, const Kind*>> declaring;
  for (const auto& category : kinds.categories())
    for (const Kind* kind : kinds.kinds(category.name))
      if (kind->candidates.has_value()) declaring.emplace_back(category.name, kind);
  storage.clear();
  storage.reserve(declaring.size());
  std::vector<DeclaredFamily> families;
  for (const auto& [category, kind] : declaring) {
    storage.push_back(std::any_cast<const CandidateDeclaration&>(kind->candidates));
    for (const auto& family : storage.back().families)
      families.push_back({&family, category == kEffectCategory ? kind->name : ""});
  }
  std::stable_sort(families.begin(), families.end(), [](const auto& a, const auto& b) {
    return a.family->position < b.family->position;
  });
  return families;
}

// Where a threshold on the temperature starts: 10 K above ambient, unless the base model never
// gets 20 K warmer, where a threshold 10 K up would never be crossed (a ratchet at its nested
// start would then have no gradient in its rate): then halfway up what it reaches.
double warm(const BaseModel& base) {
  constexpr double kUsualStart = 10.0;  // [K] above ambient
  const double rise = base.temperature_peak - base.ambient;
  if (base.temperature_peak > 0.0 && rise > 0.0 && rise < 2 * kUsualStart)
    return base.ambient + 0.5 * rise;
  return base.ambient + kUsualStart;
}

double scale_of(const BaseModel& base, CandidateScale scale) {
  const double range = base.deflection ? base.deflection->second - base.deflection->first : 0.02;
  switch (scale) {
    case CandidateScale::one:
      return 1.0;
    case CandidateScale::k1:
      return base.k1;
    case CandidateScale::k2:
      return base.k2;
    case CandidateScale::conductance:
      return base.conductance;
    case CandidateScale::ambient:
      return base.ambient;
    case CandidateScale::range:
      return range;
    case CandidateScale::k1_range:
      return base.k1 * range;
    case CandidateScale::deflection_low:
      return base.deflection ? base.deflection->first : 0.0;
    case CandidateScale::deflection_high:
      return base.deflection ? base.deflection->second : 0.0;
    case CandidateScale::deflection_sum:
      return base.deflection ? base.deflection->first + base.deflection->second : 0.0;
    case CandidateScale::power_peak:
      return base.power_peak;
    case CandidateScale::coil_scale:
      return base.lambda_scale > 0.0 ? base.lambda_scale : 1.0;
    case CandidateScale::warm:
      return warm(base);
  }
  return 1.0;
}

double value_of(const BaseModel& base, const CandidateValue& value) {
  return scale_of(base, value.scale) * value.factor / value.divisor + value.offset;
}

// Why a family cannot join this base model, or "".
std::string missing_need(const BaseModel& base, const Scenario& scenario, CandidateNeed need) {
  switch (need) {
    case CandidateNeed::temperature:
      if (base.temperature && base.heat_capacity > 0.0) return "";
      return "the muscle reports no temperature (give the reduced form's force_per_kelvin, or use "
             "the physical form)";
    case CandidateNeed::deflection:
      return base.deflection ? ""
                             : "the measurement has no deflection channel to place it in (none "
                               "replayed as a deflection, compared as one or named deflection)";
    case CandidateNeed::power:
      return base.power_peak > 0.0 ? ""
                                   : "the measurement has no power channel (none replayed as a "
                                     "power or named power)";
    case CandidateNeed::coil_output:
      return base.coil_output ? "" : "no output of the coil (inductance or L*) is compared";
    case CandidateNeed::coil_temperature_term:
      if (base.temperature && base.inductance && scenario.system->parameter_index(base.lambda_path))
        return "";
      return "the muscle's coil has no temperature term to free";
  }
  return "";
}

void add_keys(CandidateBuilder& builder, const BaseModel& base,
              const std::vector<CandidateKey>& keys) {
  for (const auto& key : keys) {
    if (key.lower && key.upper) {
      builder.free(key.key, value_of(base, key.start), value_of(base, *key.lower),
                   value_of(base, *key.upper), key.unit);
    } else {
      builder.fixed(key.key, value_of(base, key.start), key.unit);
    }
  }
}

EffectCandidate build_member(const BaseModel& base, const Scenario& scenario,
                             const CandidateFamily& family, const std::string& kind,
                             const CandidateMember& member) {
  CandidateBuilder builder(base, family.name, member.member, member.order, family.description,
                           family.signature);
  if (member.term) {
    // A law term: the muscle's section gets the key's value, the refit frees its parameter.
    const CandidateKey& key = member.sections.front().front();
    const std::string path = base.muscle + "." + member.term->section + "." + key.key;
    const auto index = scenario.system->parameter_index(path);
    const std::string unit =
        scenario.system->parameters()[static_cast<std::size_t>(*index)].declaration.unit;
    if (member.term->section != "inductance")
      throw std::logic_error("a law term of the muscle's " + member.term->section +
                             " section: the catalogue reads only its inductance section");
    builder
        .set_in_section(member.term->section, base.inductance, key.key,
                        value_of(base, member.term->given), unit)
        .free_base(path, value_of(base, key.start), value_of(base, *key.lower),
                   value_of(base, *key.upper), unit);
  } else if (member.grid) {
    const CandidateGrid& grid = *member.grid;
    for (const double point :
         log_grid(value_of(base, grid.low), value_of(base, grid.high), grid.points)) {
      builder.attach(kind).fixed(grid.key, point, grid.unit);
      add_keys(builder, base, member.sections.front());
    }
  } else {
    for (const auto& section : member.sections) {
      builder.attach(kind);
      add_keys(builder, base, section);
    }
  }
  return builder.build();
}

}  // namespace

std::string describe_candidates(const Kind& kind, bool markdown) {
  if (!kind.candidates.has_value()) return "";
  const auto& declaration = std::any_cast<const CandidateDeclaration&>(kind.candidates);
  const std::string indent = markdown ? "" : "    ";
  if (!declaration.excluded.empty())
    return indent + "discover does not try it: " + declaration.excluded + "\n";
  std::string text;
  for (const auto& family : declaration.families) {
    text += indent + "discover tries it as " + (markdown ? "`" + family.name + "`" : family.name) +
            " (" + family.description + "; signature: " + family.signature + "), members: ";
    for (std::size_t m = 0; m < family.members.size(); ++m) {
      const auto& member = family.members[m];
      text += (m ? "; " : "") + member.member + " (order " + std::to_string(member.order) + ")";
    }
    text += ".\n";
  }
  return text;
}

std::vector<std::string> effect_names() {
  std::vector<CandidateDeclaration> storage;
  std::vector<std::string> names;
  for (const auto& declared : declared_families(standard_kinds(), storage))
    if (std::find(names.begin(), names.end(), declared.family->name) == names.end())
      names.push_back(declared.family->name);  // a family two kinds declare is named once
  return names;
}

Candidates effect_candidates(const Scenario& scenario, const Context& fitted,
                             const MeasuredData& data, const std::vector<std::string>& outputs,
                             const CatalogueContext& context) {
  const BaseModel base = read_base(scenario, fitted, data, outputs, context);
  Candidates result;
  std::vector<CandidateDeclaration> storage;
  for (const auto& declared : declared_families(standard_kinds(), storage)) {
    const CandidateFamily& family = *declared.family;
    std::string missing;
    for (const CandidateNeed need : family.needs)
      if (missing.empty()) missing = missing_need(base, scenario, need);
    if (!missing.empty()) {
      const bool named = std::any_of(result.skipped.begin(), result.skipped.end(),
                                     [&](const auto& skip) { return skip.name == family.name; });
      if (!named) result.skipped.push_back({family.name, missing});  // once per family
      continue;
    }
    for (const auto& member : family.members)
      result.candidates.push_back(build_member(base, scenario, family, declared.kind, member));
  }
  return result;
}

}  // namespace tcpmsim::fit
