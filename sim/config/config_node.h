#pragma once

#include <yaml-cpp/yaml.h>

#include <functional>
#include <initializer_list>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "sim/config/config_error.h"
#include "sim/config/units.h"
#include "sim/value_check.h"

namespace tcpmsim {

struct ConfigDocument;

// How a --set's location starts: "command line (--set KEY=VALUE)". Another caller names itself
// ("tcpmsim.Scenario (set KEY=VALUE)", Python's Scenario.set).
inline constexpr const char* kCommandLineOrigin = "command line (--set ";

// What a scenario's reader asked of one key: the listing of kinds is made of these, so that it
// says what the code reads.
struct KeyRead {
  std::string path;       // in the scenario
  std::string expected;   // "quantity in N/m", "number", "integer", "one of a, b", ...
  std::string check;      // "a positive value"; empty: any
  std::string fallback;   // the default when the key is absent; empty: none
  bool optional = false;  // may be absent (asked with find or has)
  bool part = false;      // a section another kind reads (a signal, an effect)
};

// A section whose keys depend on a choice it makes: the kind its selector chose ("type:
// deflection" of a load), recorded by whoever reads the choice.
struct Variant {
  std::string category;  // "load"
  std::string selector;  // "type"
  std::string kind;      // "deflection"
};
// The keys each kind of a category takes, by kind name: what explains a key that belongs to
// another variant of its section.
using VariantKeys =
    std::function<std::map<std::string, std::set<std::string>>(const std::string& category)>;

// A --set assignment as the document applied it: its key path written out in full (an
// instance's name with its section, "muscles.m2.mechanics.k2"), its text as typed, its value.
struct Assignment {
  std::string path;
  std::string text;
  YAML::Node value;
};

// A node of a scenario file, read strictly: every value is located (file:line:col or the
// --set that produced it), typed, unit-converted to SI and range-checked; every key the
// program does not ask for is reported as unknown, with a suggestion.
class ConfigNode {
 public:
  // `overrides` are "key.path=value" strings (the CLI's --set); values are YAML. A path may
  // start with an instance's name in one of `instance_sections` (the plural sections, whose
  // keys are names): "m2.mechanics.k2" for "muscles.m2.mechanics.k2".
  // `override_origin` starts the location of an override's value (kCommandLineOrigin).
  static ConfigNode load_file(const std::string& file, const std::vector<std::string>& overrides,
                              std::shared_ptr<const UnitSystem> units,
                              const std::vector<std::string>& instance_sections = {},
                              const std::string& override_origin = kCommandLineOrigin);
  static ConfigNode load_text(const std::string& text, const std::string& name,
                              const std::vector<std::string>& overrides,
                              std::shared_ptr<const UnitSystem> units,
                              const std::vector<std::string>& instance_sections = {},
                              const std::string& override_origin = kCommandLineOrigin);

  // The --set assignments, in the order given.
  const std::vector<Assignment>& assignments() const;

  const std::string& path() const { return path_; }
  // The path of this node, or of its child `key`, as a model parameter: the scenario path with
  // each plural section's instance written by its name ("muscles.left.mechanics.k2" is
  // "left.mechanics.k2"); see name_parameters.
  std::string parameter_path() const;
  std::string parameter_path(std::string_view key) const;
  // The parameter path of any scenario path of this document.
  std::string parameter_path_of(const std::string& scenario_path) const;
  // Parameters under this node are addressed from `prefix` instead of this node's path.
  void name_parameters(const std::string& prefix) const;
  SourceLocation location() const;
  [[noreturn]] void fail(const std::string& problem) const;
  const UnitSystem& units() const;
  std::shared_ptr<const UnitSystem> shared_units() const;

  bool is_map() const { return node_.IsMap(); }
  bool is_sequence() const { return node_.IsSequence(); }
  bool is_scalar() const { return node_.IsScalar(); }
  // Whether this is the scalar `word`: a keyword a key takes in place of a value
  // (initial_deflection: equilibrium, phase: random). A look, not a read: what the key expects
  // is described by whoever reads it.
  bool is_word(std::string_view word) const { return node_.IsScalar() && node_.Scalar() == word; }

  // Declares the keys this mapping may hold, before reading them. Then a missing required key
  // is matched against misspellings among the *undeclared* keys only (k1 missing does not
  // make k2 a typo), and unknown keys get suggestions from the full set.
  void declare(std::initializer_list<std::string_view> keys) const;

  // Mapping access. `at` requires the key; `find` and `has` accept its absence.
  bool has(std::string_view key) const;
  ConfigNode at(std::string_view key) const;
  std::optional<ConfigNode> find(std::string_view key) const;
  std::vector<ConfigNode> elements() const;  // requires a sequence
  // Every key of a mapping with its node, in the file's order (each counts as asked for).
  std::vector<std::pair<std::string, ConfigNode>> entries() const;

  // This node as a typed scalar.
  double as_quantity(std::string_view si_unit, const ValueCheck& check = {}) const;
  // A difference of the quantity (a noise, a spread): converted without a unit's offset, so
  // that 0.5 degC is 0.5 K, not 273.65 K.
  double as_difference(std::string_view si_unit, const ValueCheck& check = {}) const;
  double as_number(const ValueCheck& check = {}) const;
  long as_integer(const ValueCheck& check = {}) const;
  bool as_bool() const;
  std::string as_text() const;
  std::string as_choice(std::initializer_list<std::string_view> options) const;
  std::string as_choice(const std::vector<std::string>& options) const;

  // Keyed shorthands. The *_or forms record the default in the resolved document.
  double quantity(std::string_view key, std::string_view si_unit,
                  const ValueCheck& check = {}) const;
  double quantity_or(std::string_view key, std::string_view si_unit, double fallback,
                     const ValueCheck& check = {}) const;
  double difference(std::string_view key, std::string_view si_unit,
                    const ValueCheck& check = {}) const;
  double difference_or(std::string_view key, std::string_view si_unit, double fallback,
                       const ValueCheck& check = {}) const;
  double number(std::string_view key, const ValueCheck& check = {}) const;
  double number_or(std::string_view key, double fallback, const ValueCheck& check = {}) const;
  long integer(std::string_view key, const ValueCheck& check = {}) const;
  long integer_or(std::string_view key, long fallback, const ValueCheck& check = {}) const;
  bool boolean_or(std::string_view key, bool fallback) const;
  std::string text(std::string_view key) const;
  std::string choice(std::string_view key, std::initializer_list<std::string_view> options) const;
  std::string choice(std::string_view key, const std::vector<std::string>& options) const;
  std::string choice_or(std::string_view key, std::initializer_list<std::string_view> options,
                        std::string_view fallback) const;
  std::string choice_or(std::string_view key, const std::vector<std::string>& options,
                        std::string_view fallback) const;
  // A two-element sequence [lower, upper] of quantities with lower < upper.
  std::pair<double, double> interval(std::string_view key, std::string_view si_unit,
                                     const ValueCheck& check = {}) const;

  // Every key read so far, in reading order.
  std::vector<KeyRead> reads() const;
  // Records this section as one another kind reads (described by `what`).
  void mark_part(const std::string& what) const;
  // Describes a key for the listing of kinds when the way it is read does not say it all
  // (a quantity or a keyword; an instance's name with a default).
  void describe_key(std::string_view key, const std::string& expected,
                    const std::string& fallback = "") const;

  // Records that this section is the variant `kind` of `category`, chosen by `selector`.
  void mark_variant(const std::string& category, const std::string& selector,
                    const std::string& kind) const;
  // After reading: reports the first key nobody asked for, with a "did you mean" among the keys
  // this section takes. With `variant_keys`, a key of a variant section that only other kinds of
  // its category take is reported as theirs, and their keys are no suggestions here.
  void reject_unknown_keys(const VariantKeys& variant_keys = {}) const;
  // The document as read, with overrides applied and defaults filled in.
  std::string resolved_yaml() const;
  // "file:line:col: warning: key.path: ..." for every value read outside its typical range
  // (ValueCheck::typical), in reading order.
  const std::vector<std::string>& warnings() const;

 private:
  ConfigNode(std::shared_ptr<ConfigDocument> document, YAML::Node node, std::string path);
  ConfigNode child(const YAML::Node& node, std::string path) const;
  std::string child_path(std::string_view key) const;
  void record_default(std::string_view key, const std::string& value) const;
  bool present(std::string_view key) const;  // has() without marking the key optional
  [[noreturn]] void fail_missing(std::string_view key) const;
  [[noreturn]] void fail_empty_file(std::string_view key) const;
  double read_quantity(std::string_view si_unit, const ValueCheck& check, bool difference) const;
  double read_quantity_or(std::string_view key, std::string_view si_unit, double fallback,
                          const ValueCheck& check, bool difference) const;

  std::shared_ptr<ConfigDocument> document_;
  YAML::Node node_;
  std::string path_;
  // The mapping this node is the value of, and its key (none for the root and list elements):
  // a block mapping or list starts on the line after its key, and is reported at the key, found
  // when a location is asked for.
  YAML::Node parent_;
  std::string key_;
};

// A --set path whose first key is not a section of the document but an instance of exactly
// one of `instance_sections` ("m2.mechanics.k2" with `muscles: {m2: ...}`) written out in full
// ("muscles.m2.mechanics.k2"); any other path as it is.
std::string expand_instance_path(const YAML::Node& root, const std::string& path,
                                 const std::vector<std::string>& instance_sections);

// The file a scenario's text value names (a data file): a relative path is taken from the
// scenario file's directory, or from the working directory for a --set.
std::string file_named_by(const ConfigNode& node);

// The whole of a text file; a ConfigError located at the file if it cannot be read.
std::string read_text_file(const std::string& file);

// Edit distance, for "did you mean" suggestions.
std::size_t edit_distance(std::string_view a, std::string_view b);
// The closest candidate within a small distance, or empty.
std::string closest_match(std::string_view word, const std::vector<std::string>& candidates);

}  // namespace tcpmsim
