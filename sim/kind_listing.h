#pragma once

#include <functional>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "sim/config/config_node.h"

#include "sim/config/units.h"
#include "sim/registry.h"

namespace tcpmsim {

// Every category and kind of `kinds` with the keys each reads: its unit, its range, its default.
// The keys are not written down twice: each kind's examples are built and what the code asked
// of the scenario is listed, so the listing cannot drift from the code. Sections another kind
// reads (a signal, an effect) are listed as such, not key by key. `markdown` gives tables.
// `more`, when given, adds a paragraph per kind from what layers above the engine know of it
// (Kind::candidates: how `tcpmsim discover` tries an effect), or "".
using KindNotes = std::function<std::string(const Kind& kind, bool markdown)>;
std::string describe_kinds(const KindRegistry& kinds, std::shared_ptr<const UnitSystem> units,
                           bool markdown, const KindNotes& more = {});

// The keys one kind's examples read under its section (relative paths, "[]" for any index).
struct KindKey {
  std::string key;
  std::string expected;
  std::string check;
  std::string fallback;
  bool optional = false;
  // A key required only when the optional section above it is given ("inductance" for
  // inductance.lambda_l: a muscle without self-sensing has neither), or only when a choice of
  // the kind has these values ("mode: power" for a Joule drive's power: of power, duty and
  // current, the mode's one is required).
  std::string required_with;
  // A key required unless another is given: examples read exactly one of the two (a multisine's
  // offset or its range).
  std::string required_without;
};
// Where an example's scenario is read from: `name` as given, or, when the example has files,
// a file of that name in a new temporary directory that holds them (removed with this).
class ExampleScenario {
 public:
  ExampleScenario(const KindExample& example, const std::string& name);
  ~ExampleScenario();
  ExampleScenario(const ExampleScenario&) = delete;
  ExampleScenario& operator=(const ExampleScenario&) = delete;
  const std::string& name() const { return name_; }

 private:
  std::string directory_;
  std::string name_;
};

std::vector<KindKey> kind_keys(const KindRegistry& kinds, const Kind& kind,
                               std::shared_ptr<const UnitSystem> units);

// The names of the keys that one kind's examples read directly in its section, listed or not
// ("bundle", "deflection", "load_cell_resolution", "muscle", "muscles" for a deflection load).
std::set<std::string> kind_key_names(const KindRegistry& kinds, const Kind& kind,
                                     std::shared_ptr<const UnitSystem> units);

// For ConfigNode::reject_unknown_keys: the key names of every kind of a category, from their
// examples (built only when asked, for a message). Refers to `kinds`: use it while they live.
VariantKeys variant_keys(const KindRegistry& kinds, std::shared_ptr<const UnitSystem> units);

}  // namespace tcpmsim
