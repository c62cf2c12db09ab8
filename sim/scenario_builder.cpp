#include "sim/scenario_builder.h"

#include <set>

namespace tcpmsim {

namespace {
std::string article(const std::string& noun) {
  return (noun.find_first_of("aeiou") == 0 ? "an " : "a ") + noun;
}

// Names that would collide with the record's own datasets and groups or the scenario's
// sections.
const std::set<std::string> kReservedNames{"time", "inputs", "scenario", "output", "solver"};

void check_name(const ConfigNode& node, const std::string& name) {
  if (name.empty() || name.find_first_of("./[] \t") != std::string::npos) {
    node.fail(
        "expected an instance name without dots, slashes, brackets or spaces (it names "
        "the record's group), got '" +
        name + "'");
  }
  if (name.find('/') != std::string::npos)
    node.fail("expected an instance name without slashes, got '" + name + "'");
  if (kReservedNames.count(name)) node.fail("'" + name + "' is reserved; choose another name");
}
}  // namespace

ScenarioBuilder::ScenarioBuilder(const KindRegistry& kinds, const ConfigNode& root,
                                 ScenarioSettings settings)
    : kinds_(kinds), settings_(std::move(settings)) {
  declare_instances(root);
}

void ScenarioBuilder::declare_instances(const ConfigNode& root) {
  std::set<std::string> names;
  auto declare = [&](const Category& category, const ConfigNode& node, const std::string& name,
                     const ConfigNode& located) {
    check_name(located, name);
    if (!names.insert(name).second)
      located.fail("two instances are named '" + name + "'; names must be unique");
    by_category_[category.name].push_back(instances_.size());
    instances_.push_back({category.name, name, node, &kinds_.select(category.name, node)});
  };
  for (const Category& category : kinds_.categories()) {
    if (!category.top_level()) continue;
    if (const auto single = root.find(category.name))
      declare(category, *single, category.name, *single);
    if (const auto plural = root.find(category.plural)) {
      if (!plural->is_map())
        plural->fail("expected a mapping of " + category.name + " names to their sections");
      for (const auto& [name, node] : plural->entries()) {
        node.name_parameters(name);
        declare(category, node, name, node);
      }
    }
  }
  for (const auto& instance : instances_) by_name_[instance.name] = &instance;
}

std::unique_ptr<Signal> ScenarioBuilder::signal(const ConfigNode& node,
                                                std::string_view si_unit) const {
  return read_signal(node, si_unit, signals());
}

std::vector<const InstanceDeclaration*> ScenarioBuilder::instances(
    std::string_view category) const {
  std::vector<const InstanceDeclaration*> found;
  if (const auto indices = by_category_.find(category); indices != by_category_.end()) {
    for (const std::size_t index : indices->second) found.push_back(&instances_[index]);
  }
  return found;
}

const InstanceDeclaration* ScenarioBuilder::instance(std::string_view name) const {
  const auto found = by_name_.find(std::string(name));
  return found == by_name_.end() ? nullptr : found->second;
}

const InstanceDeclaration& ScenarioBuilder::named(const ConfigNode& name_node,
                                                  std::string_view category) const {
  const std::string name = name_node.as_text();
  const InstanceDeclaration* found = instance(name);
  if (!found || found->category != category) {
    std::vector<std::string> candidates;
    for (const auto* other : instances(category)) candidates.push_back(other->name);
    std::string listed;
    for (const auto& candidate : candidates) listed += (listed.empty() ? "" : ", ") + candidate;
    const std::string suggestion = closest_match(name, candidates);
    name_node.fail("no " + std::string(category) + " named '" + name + "'" +
                   (suggestion.empty() ? "" : " (did you mean '" + suggestion + "'?)") +
                   (listed.empty() ? "" : "; the scenario's: " + listed));
  }
  return *found;
}

const InstanceDeclaration& ScenarioBuilder::linked(const ConfigNode& node, std::string_view key,
                                                   std::string_view category) const {
  const std::string what(category);
  if (const auto name = node.find(key)) {
    const InstanceDeclaration& found = named(*name, category);
    node.describe_key(key, "name of " + article(what), "the only " + what);
    return found;
  }
  node.describe_key(key, "name of " + article(what), "the only " + what);
  if (const auto member = member_links_.find(category); member != member_links_.end())
    return *by_name_.at(member->second);
  const auto indices = by_category_.find(category);
  const std::size_t count = indices == by_category_.end() ? 0 : indices->second.size();
  if (count == 1) return instances_[indices->second.front()];
  const auto candidates = instances(category);
  if (candidates.empty())
    node.fail("needs a " + std::string(category) + ", and the scenario has none");
  node.fail("the scenario has several " + kinds_.category(category).plural + "; say which with '" +
            std::string(key) + ": <name>'");
}

std::vector<const InstanceDeclaration*> ScenarioBuilder::linked_all(
    const ConfigNode& node, std::string_view key, std::string_view plural_key,
    std::string_view category) const {
  node.describe_key(plural_key, "names of " + kinds_.category(category).plural,
                    "the one named by '" + std::string(key) + "'");
  if (const auto list = node.find(plural_key)) {
    std::vector<const InstanceDeclaration*> found;
    std::set<std::string> seen;
    for (const auto& element : list->elements()) {
      const InstanceDeclaration& instance = named(element, category);
      if (!seen.insert(instance.name).second)
        element.fail("'" + instance.name + "' is listed twice");
      found.push_back(&instance);
    }
    if (found.empty()) list->fail("expected at least one " + std::string(category));
    if (node.has(key))
      node.at(key).fail("give either '" + std::string(key) + "' or '" + std::string(plural_key) +
                        "', not both");
    return found;
  }
  return {&linked(node, key, category)};
}

void ScenarioBuilder::build_member(const std::string& category, const std::string& name,
                                   const ConfigNode& node, const Kind& kind,
                                   const std::map<std::string, std::string>& links) {
  if (by_name_.count(name)) throw std::logic_error("two instances are named '" + name + "'");
  by_name_[name] = &members_.emplace_back(InstanceDeclaration{category, name, node, &kind});
  for (const auto& [linked_category, member] : links) {
    if (!by_name_.count(member))
      throw std::logic_error("member " + name + " links to no instance named '" + member + "'");
  }
  // The member's parameters are its own ("b/m03.mechanics.k1"); afterwards the shared section
  // names no member's, so that a --set of its keys rebuilds every member instead of reaching
  // the last one built.
  const std::string shared = node.parameter_path();
  const auto saved = member_links_;
  for (const auto& [linked_category, member] : links) member_links_[linked_category] = member;
  node.name_parameters(name);
  auto restore = [&] {
    member_links_ = saved;
    node.name_parameters(shared);
  };
  try {
    kinds_.builder<InstanceBuilder>(kind)(node, name, *this);
  } catch (...) {
    restore();
    throw;
  }
  restore();
}

void ScenarioBuilder::run_checks() const {
  for (const auto& check : checks_) check();
}

}  // namespace tcpmsim
