#pragma once

#include <any>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "sim/config/config_error.h"
#include "sim/config/config_node.h"
#include "sim/registry.h"
#include "sim/signal_reading.h"
#include "sim/system.h"

namespace tcpmsim {

struct ScenarioSettings {
  std::string name;
  std::string description;
  double duration = 0.0;  // [s]
  std::uint64_t seed = 0;
  double output_interval = 0.0;  // [s]
  double output_start = 0.0;     // [s] first recorded time
  // The record's deflate level, 0 for none (output.compression): zlib at level 1 costs about
  // twice the integration of a typical run, so records are uncompressed unless asked.
  int compression_level = 0;
  std::string measurement_file;         // measurement.file, found beside the scenario; empty: none
  SourceLocation output_rate_location;  // where output.rate was given, for the record-size check
};

// An instance a scenario declares: a section of a top-level category, its name and its kind.
struct InstanceDeclaration {
  std::string category;
  std::string name;
  ConfigNode node;
  const Kind* kind;
};

// What the kinds' builders share while a scenario is built: the registry, the scenario's
// settings, the system under construction, the instances the scenario declares (all of them,
// known before any is built) and the facts the built ones publish for those built after them
// (a muscle's coil law for its drive, a drive's PWM period for its estimator).
class ScenarioBuilder {
 public:
  ScenarioBuilder(const KindRegistry& kinds, const ConfigNode& root, ScenarioSettings settings);

  const KindRegistry& kinds() const { return kinds_; }
  const ScenarioSettings& settings() const { return settings_; }
  SystemBuilder& system() { return system_; }
  SignalContext signals() const {
    return {settings_.seed, settings_.duration, &kinds_, settings_.measurement_file};
  }
  // A signal of the scenario, its values in `si_unit`.
  std::unique_ptr<Signal> signal(const ConfigNode& node, std::string_view si_unit) const;

  const std::vector<InstanceDeclaration>& instances() const { return instances_; }
  std::vector<const InstanceDeclaration*> instances(std::string_view category) const;
  const InstanceDeclaration* instance(std::string_view name) const;
  // The instance of `category` a section names under `key` ("muscle: left"); without the key,
  // the only instance of that category. A located error if there is none, or several.
  const InstanceDeclaration& linked(const ConfigNode& node, std::string_view key,
                                    std::string_view category) const;
  // Several: the names listed under `plural_key`, or the one under `key`, or the only one.
  std::vector<const InstanceDeclaration*> linked_all(const ConfigNode& node, std::string_view key,
                                                     std::string_view plural_key,
                                                     std::string_view category) const;

  // Builds an instance that is part of another one (a bundle's member muscle "b/m003", its
  // drive "b/m003/drive") from a section the other instance holds (a template): `kind`'s builder
  // runs with `links` answering the link keys the section leaves out ({muscle: "b/m003"}), and the
  // member can be linked to by name afterwards. The section's parameters are the member's while
  // it is built ("b/m03.mechanics.k1"), and nobody's after. Members do not count as "the only"
  // instance of their category, and their names, which hold a slash, cannot collide with declared
  // ones.
  void build_member(const std::string& category, const std::string& name, const ConfigNode& node,
                    const Kind& kind, const std::map<std::string, std::string>& links);

  template <typename Facts>
  void publish(const std::string& instance, Facts facts) {
    facts_[instance] = std::move(facts);
  }
  // What `instance` published, if it published facts of this type.
  template <typename Facts>
  const Facts* facts(const std::string& instance) const {
    const auto found = facts_.find(instance);
    return found == facts_.end() ? nullptr : std::any_cast<Facts>(&found->second);
  }

  // A check to run once every instance is built (a drive no controller commands needs a power
  // signal after all).
  void after_building(std::function<void()> check) { checks_.push_back(std::move(check)); }
  void run_checks() const;

 private:
  void declare_instances(const ConfigNode& root);
  const InstanceDeclaration& named(const ConfigNode& name_node, std::string_view category) const;

  const KindRegistry& kinds_;
  ScenarioSettings settings_;
  SystemBuilder system_;
  std::vector<InstanceDeclaration> instances_;  // declared in the scenario
  std::deque<InstanceDeclaration> members_;     // built as parts of others (stable addresses)
  std::map<std::string, const InstanceDeclaration*> by_name_;                 // either
  std::map<std::string, std::vector<std::size_t>, std::less<>> by_category_;  // declared only
  std::map<std::string, std::string, std::less<>> member_links_;  // category -> member, while built
  std::map<std::string, std::any> facts_;
  std::vector<std::function<void()>> checks_;
};

}  // namespace tcpmsim
