#include "sim/kind_listing.h"

#include <stdlib.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include <map>
#include <optional>
#include <set>
#include <sstream>

#include <yaml-cpp/yaml.h>

#include "sim/config/config_error.h"
#include "sim/config/config_node.h"
#include "sim/scenario.h"

namespace tcpmsim {

namespace {

bool under(const std::string& path, const std::string& root) {
  return path.size() > root.size() && path.compare(0, root.size(), root) == 0 &&
         (path[root.size()] == '.' || path[root.size()] == '[');
}

// "values[3]" -> "values[]": one line for all elements.
std::string generic(const std::string& key) {
  std::string result;
  for (std::size_t i = 0; i < key.size(); ++i) {
    result += key[i];
    if (key[i] != '[') continue;
    while (i + 1 < key.size() && key[i + 1] >= '0' && key[i + 1] <= '9') ++i;
  }
  return result;
}

std::string row(const KindKey& key, bool markdown) {
  std::string range = key.check.empty() ? "" : key.check;
  const std::string within = markdown ? "`" + key.required_with + "`" : key.required_with;
  const std::string without = markdown ? "`" + key.required_without + "`" : key.required_without;
  const std::string fallback = !key.fallback.empty()           ? "default " + key.fallback
                               : key.optional                  ? "optional"
                               : !key.required_with.empty()    ? "required with " + within
                               : !key.required_without.empty() ? "required without " + without
                                                               : "required";
  std::ostringstream line;
  if (markdown) {
    line << "| `" << key.key << "` | " << key.expected << " | " << range << " | " << fallback
         << " |\n";
  } else {
    line << "    " << key.key << ' ';
    for (std::size_t pad = key.key.size(); pad < 35; ++pad) line << ' ';
    line << key.expected << (range.empty() ? "" : ", " + range) << "; " << fallback << "\n";
  }
  return line.str();
}

}  // namespace

ExampleScenario::ExampleScenario(const KindExample& example, const std::string& name)
    : name_(name) {
  if (example.files.empty()) return;
  std::string pattern = (std::filesystem::temp_directory_path() / "tcpmsim-example-XXXXXX");
  if (!mkdtemp(pattern.data())) {
    throw std::runtime_error("cannot make a temporary directory for an example's files");
  }
  directory_ = pattern;
  for (const auto& [file, content] : example.files) {
    std::ofstream(std::filesystem::path(directory_) / file) << content;
  }
  name_ = (std::filesystem::path(directory_) / name).string();
}

ExampleScenario::~ExampleScenario() {
  std::error_code ignored;
  if (!directory_.empty()) std::filesystem::remove_all(directory_, ignored);
}

namespace {
// What one example reads under its kind's section: each read with its path relative to the
// section ("deflection", "mechanics.k1").
std::vector<KeyRead> example_reads(const KindRegistry& kinds, const Kind& kind,
                                   const KindExample& example,
                                   std::shared_ptr<const UnitSystem> units) {
  const ExampleScenario where(example, kind.name + "_example.yaml");
  const ConfigNode root = ConfigNode::load_text(example.text, where.name(), {}, units);
  build_scenario(root, kinds);
  std::vector<KeyRead> reads;
  for (KeyRead read : root.reads()) {
    if (!under(read.path, example.node)) continue;
    read.path = read.path.substr(example.node.size() + 1);
    reads.push_back(std::move(read));
  }
  return reads;
}
}  // namespace

namespace {
// The node at `path` ("muscle.effects[0].force") in `root`, part of `root` (it walks with
// reset(), not assignment, which would overwrite); none where the path leads nowhere.
std::optional<YAML::Node> node_at(const YAML::Node& root, const std::string& path) {
  YAML::Node node = root;
  std::string rest = path;
  while (!rest.empty()) {
    const std::size_t dot = rest.find('.');
    const std::string part = rest.substr(0, dot);
    rest = dot == std::string::npos ? "" : rest.substr(dot + 1);
    const std::size_t bracket = part.find('[');
    if (!node.IsMap()) return std::nullopt;
    YAML::Node next = node[part.substr(0, bracket)];
    if (bracket != std::string::npos) {
      if (!next.IsSequence()) return std::nullopt;
      next.reset(next[std::stoul(part.substr(bracket + 1))]);
    }
    if (!next) return std::nullopt;
    node.reset(next);
  }
  return node;
}

// The value an example gives the choice at `path` below its section ("mode" -> "duty"), read
// from its text; "" where it is not a plain scalar there.
std::string example_choice(const KindExample& example, const std::string& path) {
  const auto node = node_at(YAML::Load(example.text), example.node + "." + path);
  return node && node->IsScalar() ? node->Scalar() : "";
}

// What one example reads: its keys, and the value of each choice it makes.
struct ExampleKeys {
  std::string node;  // the section the example shows
  std::set<std::string> keys;
  std::map<std::string, std::string> choices;
};

// Whether the examples show one section (their keys compare): a kind may also be shown through
// parts of its section read elsewhere (a thermal form's muscle.thermal).
bool one_section(const std::vector<ExampleKeys>& examples) {
  return std::all_of(examples.begin(), examples.end(), [&](const ExampleKeys& example) {
    return example.node == examples.front().node;
  });
}

// Which examples read `key`.
std::vector<bool> readers(const std::string& key, const std::vector<ExampleKeys>& examples) {
  std::vector<bool> reads;
  for (const auto& example : examples) reads.push_back(example.keys.count(key) > 0);
  return reads;
}

// Whether a key needs a condition at all: the examples show one section, and some of them do not
// read it.
bool read_in_some(const std::vector<bool>& reads, const std::vector<ExampleKeys>& examples) {
  return one_section(examples) &&
         !std::all_of(reads.begin(), reads.end(), [](bool read) { return read; });
}

// For a key that some examples read and others do not: the choice that decides it, made in
// every example, in the key's section or one above it, and with other values where the key is
// not read: "mode: duty" (or "mode: duty or current"); "" if none does.
std::string deciding_choice(const std::string& key, const std::vector<ExampleKeys>& examples) {
  const std::vector<bool> reads = readers(key, examples);
  if (!read_in_some(reads, examples)) return "";
  for (const auto& [choice, ignored] : examples.front().choices) {
    const std::size_t dot = choice.rfind('.');
    if (dot != std::string::npos && !under(key, choice.substr(0, dot))) continue;
    std::set<std::string> with, without;
    bool everywhere = true;
    for (std::size_t i = 0; i < examples.size() && everywhere; ++i) {
      const auto found = examples[i].choices.find(choice);
      everywhere = found != examples[i].choices.end();
      if (everywhere) (reads[i] ? with : without).insert(found->second);
    }
    if (!everywhere || with.empty()) continue;
    bool apart = true;
    for (const auto& value : with) apart = apart && !without.count(value);
    if (!apart) continue;
    std::string values;
    for (const auto& value : with) values += (values.empty() ? "" : " or ") + value;
    return choice + ": " + values;
  }
  return "";
}
// "mechanics" for "mechanics.k1", "" for "k1" and "range[]".
std::string parent_section(const std::string& key) {
  const std::size_t dot = key.rfind('.');
  return dot == std::string::npos ? "" : key.substr(0, dot);
}

// For a key some examples read: the first other key without a default (and, unless
// `optional_too`, required), of its own section or the section the key names (a scalar or its
// section), that exactly the other examples read; by its name in the section ("range" for
// "range[]"); "" if none.
std::string alternative(const std::string& key, const std::vector<KindKey>& keys,
                        const std::vector<ExampleKeys>& examples, bool optional_too = false) {
  const std::vector<bool> reads = readers(key, examples);
  if (!read_in_some(reads, examples)) return "";
  for (const auto& other : keys) {
    if (other.key == key || (other.optional && !optional_too) || !other.fallback.empty()) continue;
    if (parent_section(other.key) != parent_section(key) && !under(other.key, key) &&
        !under(key, other.key))
      continue;
    const std::vector<bool> others = readers(other.key, examples);
    bool complement = true;
    for (std::size_t i = 0; i < reads.size() && complement; ++i) complement = reads[i] != others[i];
    if (complement) return other.key.substr(0, other.key.find('['));
  }
  return "";
}

// Whether an example still builds with `key` (a path of plain names below its section) taken
// out: a key its reader asks for with has() may still be needed when another key is absent
// (a hysteresis element's force, without its radius).
bool builds_without(const KindRegistry& kinds, const Kind& kind, const KindExample& example,
                    const std::string& key, std::shared_ptr<const UnitSystem> units) {
  if (key.find('[') != std::string::npos) return true;
  const YAML::Node root = YAML::Load(example.text);
  const std::string path = example.node + "." + key;
  const std::size_t dot = path.rfind('.');
  auto section = node_at(root, path.substr(0, dot));
  if (!section || !section->IsMap()) return true;
  section->remove(path.substr(dot + 1));
  const ExampleScenario where(example, kind.name + "_example.yaml");
  try {
    build_scenario(ConfigNode::load_text(YAML::Dump(root), where.name(), {}, units), kinds);
  } catch (const ConfigError&) {
    return false;
  }
  return true;
}
}  // namespace

std::vector<KindKey> kind_keys(const KindRegistry& kinds, const Kind& kind,
                               std::shared_ptr<const UnitSystem> units) {
  std::vector<KindKey> keys;
  std::map<std::string, std::size_t> seen;
  std::vector<ExampleKeys> per_example;
  for (const auto& example : kind.examples) {
    std::vector<std::string> parts;              // sections below this one that another kind reads
    std::vector<std::string> optional_sections;  // sections asked for with has or find
    ExampleKeys here;
    here.node = example.node;
    for (const auto& read : example_reads(kinds, kind, example, units)) {
      bool inside_part = false;
      for (const auto& part : parts) inside_part = inside_part || under(read.path, part);
      if (inside_part) continue;
      if (read.part) parts.push_back(read.path);
      if (read.expected.empty() && read.optional) optional_sections.push_back(read.path);
      if (read.expected.empty()) continue;
      const std::string key = generic(read.path);
      if (key == kinds.category(kind.category).selector) continue;  // said by the category
      here.keys.insert(key);
      if (read.expected.rfind("one of ", 0) == 0) {
        if (const std::string value = example_choice(example, read.path); !value.empty())
          here.choices[key] = value;
      }
      const auto [found, added] = seen.try_emplace(key, keys.size());
      if (added) {
        std::string within;  // the innermost optional section holding the key
        for (const auto& section : optional_sections)
          if (under(read.path, section) && section.size() > within.size()) within = section;
        keys.push_back(
            {key, read.expected, read.check, read.fallback, read.optional, generic(within), ""});
      } else {
        keys[found->second].optional = keys[found->second].optional || read.optional;
      }
    }
    per_example.push_back(std::move(here));
  }
  // A key required in some examples only: required with the choice those examples make, or
  // without the key the other examples read instead.
  for (auto& key : keys) {
    if (key.fallback.empty() && !key.optional && key.required_with.empty())
      key.required_with = deciding_choice(key.key, per_example);
  }
  for (auto& key : keys) {
    if (key.fallback.empty() && !key.optional && key.required_with.empty())
      key.required_without = alternative(key.key, keys, per_example);
  }
  // A key asked for with has() is optional, unless another key replaces it: some examples read
  // one and the others the other, and an example without it fails to build.
  for (auto& key : keys) {
    if (!key.optional || !key.fallback.empty()) continue;
    const std::string other = alternative(key.key, keys, per_example, true);
    if (other.empty()) continue;
    const auto reading = std::find_if(per_example.begin(), per_example.end(),
                                      [&](const ExampleKeys& e) { return e.keys.count(key.key); });
    const auto example = kind.examples.begin() + (reading - per_example.begin());
    if (builds_without(kinds, kind, *example, key.key, units)) continue;
    key.optional = false;
    key.required_without = other;
  }
  return keys;
}

std::set<std::string> kind_key_names(const KindRegistry& kinds, const Kind& kind,
                                     std::shared_ptr<const UnitSystem> units) {
  std::set<std::string> names;
  for (const auto& example : kind.examples) {
    for (const auto& read : example_reads(kinds, kind, example, units))
      names.insert(read.path.substr(0, read.path.find_first_of(".[")));
  }
  return names;
}

VariantKeys variant_keys(const KindRegistry& kinds, std::shared_ptr<const UnitSystem> units) {
  return [&kinds, units](const std::string& category) {
    std::map<std::string, std::set<std::string>> keys;
    for (const Kind* kind : kinds.kinds(category))
      keys[kind->name] = kind_key_names(kinds, *kind, units);
    return keys;
  };
}

std::string describe_kinds(const KindRegistry& kinds, std::shared_ptr<const UnitSystem> units,
                           bool markdown, const KindNotes& more) {
  std::ostringstream out;
  if (markdown) {
    out << "# Kinds of component and signal\n\nMade by `tcpmsim kinds --markdown` from the "
           "registry: each kind's examples are built and the keys its code reads are listed. "
           "Quantities take any unit convertible to the one shown. The last column says whether "
           "a key must be given: *required*; *optional*; *default* and the value taken without "
           "it; *required with* a choice (the key is read only when that choice is made, as a "
           "Joule drive's `power` with `mode: power`); or *required without* another key (give "
           "one of the two, as a hysteresis element's `force` or `radius`).\n\n";
  }
  for (const Category& category : kinds.categories()) {
    if (markdown) {
      out << "## " << category.name << "\n\n" << category.summary << ".";
    } else {
      out << category.name << ": " << category.summary << ".";
    }
    if (category.top_level()) {
      out << " Sections `" << category.name << ":` (one, named " << category.name << ") or `"
          << category.plural << ": {<name>: ...}`.";
    }
    if (!category.selector.empty()) {
      out << " The kind is named by `" << category.selector << "`"
          << (category.default_kind.empty() ? "" : " (default " + category.default_kind + ")")
          << (category.scalar_kind.empty() ? "" : "; a bare quantity is a " + category.scalar_kind)
          << ".";
    }
    if (category.name == "signal") {
      out << " Values are in the unit of what the signal drives (W in these examples).";
    }
    out << "\n\n";
    for (const Kind* kind : kinds.kinds(category.name)) {
      if (markdown) {
        out << "### " << category.name << " `" << kind->name << "`\n\n"
            << kind->summary << ".\n\n| key | expects | range | default |\n|---|---|---|---|\n";
      } else {
        out << "  " << kind->name << ": " << kind->summary << "\n";
      }
      for (const auto& key : kind_keys(kinds, *kind, units)) out << row(key, markdown);
      out << "\n";
      if (more) {
        if (const std::string notes = more(*kind, markdown); !notes.empty()) out << notes << "\n";
      }
    }
  }
  return out.str();
}

}  // namespace tcpmsim
