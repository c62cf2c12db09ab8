#pragma once

#include <any>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace tcpmsim {

class ConfigNode;
class ScenarioBuilder;

// What a section of a scenario holds. A top-level category is a kind of instance a scenario
// may hold any number of ("muscle", "drive"): one under its singular key, named after it
// (`drive:`), or several under its plural key, named by their keys (`drives: {left: ..,
// right: ..}`). Top-level categories are built by increasing `order`. Other
// categories are parts that a kind reads inside its own section (a muscle's thermal force, its
// effects; every signal).
struct Category {
  std::string name;          // "drive"
  std::string plural;        // "drives"; empty for parts
  std::string selector;      // the key naming the kind ("model", "type", "form"); empty: one kind
  std::string default_kind;  // when the selector is absent; empty: the selector is required
  std::string summary;
  std::string scalar_kind;  // the kind that reads a bare scalar section (a constant signal)
  // Top-level categories are built by increasing order, so that what an instance links to is
  // built before it (muscles, then their drives, estimators, controllers, then loads).
  int order = 0;
  bool top_level() const { return !plural.empty(); }
};

// A scenario that shows a kind: `text` is a whole scenario, `node` the path of the kind's
// section in it ("drive", "muscle.effects[0]", "drive.power").
struct KindExample {
  std::string text;
  std::string node;
  // Files beside the scenario, (name, content): the data file a replayed signal reads.
  std::vector<std::pair<std::string, std::string>> files = {};
};

// A kind of component (or signal) a scenario may name, with what builds it. The builder's
// type depends on the category: InstanceBuilder for top-level categories, SignalBuilder for
// signals, and for parts whatever the kind that reads them declares.
struct Kind {
  std::string category;
  std::string name;
  std::string summary;
  std::vector<KindExample> examples;
  std::any builder;
  // What tools above the model know of the kind: for an effect (and the muscle's own law
  // terms), how `tcpmsim discover` tries it (models/effects/effect_candidates.h).
  std::any candidates = {};
};

// Builds one instance of a top-level category from its section.
using InstanceBuilder = std::function<void(const ConfigNode& node, const std::string& instance,
                                           ScenarioBuilder& build)>;

// Every kind by name, in the manner of Cantera's ReactorFactory: the scenario builder and every
// kind that reads parts ask it, so that no builder names the models it builds. Each layer
// registers its own kinds (signals/, models/, controllers/); kinds/standard_kinds.h assembles
// them.
class KindRegistry {
 public:
  void add_category(Category category);
  void add(Kind kind);

  // In build order: top-level categories by `order`, then the others as registered.
  const std::vector<Category>& categories() const { return categories_; }
  const Category& category(std::string_view name) const;
  std::vector<const Kind*> kinds(std::string_view category) const;  // in registration order
  std::vector<std::string> kind_names(std::string_view category) const;
  const Kind* find(std::string_view category, std::string_view name) const;
  // The kind, which must be registered (a category's default or scalar kind): std::logic_error
  // if it is not.
  const Kind& registered(std::string_view category, std::string_view name) const;

  // The kind a section names: its selector read with the category's kinds as the choices (or
  // the default when absent), recorded in the section as its variant. A located ConfigError for
  // an unknown kind.
  const Kind& select(std::string_view category, const ConfigNode& node) const;

  // The builder of `kind`, of the type its category uses (std::logic_error if not).
  template <typename Builder>
  const Builder& builder(const Kind& kind) const {
    if (const auto* found = std::any_cast<Builder>(&kind.builder)) return *found;
    throw std::logic_error("kind '" + kind.name + "' of '" + kind.category +
                           "' has a builder of another type");
  }

 private:
  std::vector<Category> categories_;
  std::vector<Kind> kinds_;
};

}  // namespace tcpmsim
