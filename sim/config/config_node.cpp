#include "sim/config/config_node.h"

#include <filesystem>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "sim/config/yaml_scan.h"

namespace tcpmsim {

// ---------------------------------------------------------------------------------------------
// Suggestions

std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> previous(b.size() + 1), current(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) previous[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    current[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t substitution = previous[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1);
      current[j] = std::min({previous[j] + 1, current[j - 1] + 1, substitution});
    }
    std::swap(previous, current);
  }
  return previous[b.size()];
}

std::string closest_match(std::string_view word, const std::vector<std::string>& candidates) {
  std::string best;
  std::size_t best_distance = std::max<std::size_t>(2, word.size() / 3) + 1;
  for (const auto& candidate : candidates) {
    const std::size_t distance = edit_distance(word, candidate);
    if (distance < best_distance) {
      best_distance = distance;
      best = candidate;
    }
  }
  return best;
}

// ---------------------------------------------------------------------------------------------
// The document

struct ConfigDocument {
  std::string file;
  std::string override_origin = kCommandLineOrigin;  // "command line (--set "
  YAML::Node root;
  YAML::Node resolved;
  bool empty = false;  // the file holds no document (blank, or only comments)
  std::vector<Assignment> overrides;
  // Mappings a --set added on its way to its key ("foo" for --set foo.bar=1), with its text.
  std::map<std::string, std::string> introduced;
  std::map<std::string, Variant> variants;  // section path -> the kind its selector chose
  std::map<std::string, std::set<std::string>> known_keys;  // mapping path -> asked keys
  std::set<std::string> consumed;
  std::shared_ptr<const UnitSystem> units;
  std::map<std::string, std::string> parameter_prefixes;  // scenario path -> parameter path
  std::vector<KeyRead> reads;
  std::map<std::string, std::size_t> read_at;  // path -> index in reads
  std::vector<std::string> warnings;           // located, in reading order

  KeyRead& read(const std::string& path) {
    const auto [found, added] = read_at.try_emplace(path, reads.size());
    if (added) reads.push_back({path, {}, {}, {}, false, false});
    return reads[found->second];
  }
  void log(const std::string& path, std::string expected, const ValueCheck& check = {}) {
    KeyRead& entry = read(path);
    if (entry.part) return;  // what the section is says more than how it was read
    entry.expected = std::move(expected);
    entry.check = check.unbounded() ? "" : check.expectation();
    if (check.has_typical_range())
      entry.check += (entry.check.empty() ? "" : "; ") + check.typical_text();
  }
};

namespace {

std::string quantity_text(std::string_view si_unit) {
  return si_unit == "1" ? std::string("number") : "quantity in " + std::string(si_unit);
}

std::string join(std::string_view path, std::string_view key) {
  return path.empty() ? std::string(key) : std::string(path) + "." + std::string(key);
}

bool is_prefix_path(std::string_view prefix, std::string_view path) {
  if (!path.starts_with(prefix)) return false;
  return path.size() == prefix.size() || path[prefix.size()] == '.' || path[prefix.size()] == '[';
}

SourceLocation command_line(const ConfigDocument& document, const std::string& assignment) {
  return {document.file, 0, 0, document.override_origin + assignment + ")"};
}

// Where the value or key at `path` came from: the last --set that gave it or a section above it,
// or that introduced it ("foo" of --set foo.bar=1); else its mark in the file.
SourceLocation locate(const ConfigDocument& document, const std::string& path,
                      const YAML::Mark& mark) {
  for (auto assignment = document.overrides.rbegin(); assignment != document.overrides.rend();
       ++assignment) {
    if (is_prefix_path(assignment->path, path)) return command_line(document, assignment->text);
  }
  if (const auto found = document.introduced.find(path); found != document.introduced.end())
    return command_line(document, found->second);
  if (mark.is_null()) return {document.file, 0, 0, {}};
  return {document.file, mark.line + 1, mark.column + 1, {}};
}

// What a node is, with its article: "a mapping", "an empty value".
std::string node_kind(const YAML::Node& node) {
  if (node.IsMap()) return "a mapping";
  if (node.IsSequence()) return "a sequence";
  if (node.IsNull()) return "an empty value";
  return "a scalar";
}

std::string trim(std::string_view text) {
  const auto first = text.find_first_not_of(" \t");
  if (first == std::string_view::npos) return {};
  const auto last = text.find_last_not_of(" \t");
  return std::string(text.substr(first, last - first + 1));
}

// Bounds on what a configuration may expand to: YAML aliases can refer to themselves (a cycle)
// or nest to expand exponentially (the "billion laughs"), which a recursive walk would follow
// until the stack or the memory gives out.
constexpr int kMaxDepth = 64;
constexpr long kMaxNodes = 1000000;

std::string position_text(const YAML::Mark& mark) {
  return std::to_string(mark.line + 1) + ":" + std::to_string(mark.column + 1);
}

struct DocumentWalk {
  const std::string& file;
  long nodes = 0;

  [[noreturn]] void refuse(const YAML::Node& node, const std::string& what) const {
    const auto mark = node.Mark();
    throw ConfigError({file, mark.line + 1, mark.column + 1, {}}, "",
                      what +
                          " (are YAML aliases nested in one another, or referring to "
                          "themselves?); a configuration needs neither");
  }

  // A key is a name, given once in its mapping.
  void visit_map(const YAML::Node& node, int depth, const std::string& path) {
    std::map<std::string, YAML::Mark> seen;
    for (const auto& entry : node) {
      const auto mark = entry.first.Mark();
      if (!entry.first.IsScalar()) {
        throw ConfigError({file, mark.line + 1, mark.column + 1, {}}, path,
                          "expected a key name, got a " +
                              std::string(entry.first.IsMap() ? "mapping" : "sequence"));
      }
      const std::string key = entry.first.as<std::string>();
      const auto [first, added] = seen.try_emplace(key, mark);
      if (!added) {
        throw ConfigError(
            {file, mark.line + 1, mark.column + 1, {}}, join(path, key),
            "duplicate key '" + key + "' (first given at " + position_text(first->second) + ")");
      }
      visit(entry.second, depth + 1, join(path, key));
    }
  }

  void visit(const YAML::Node& node, int depth, const std::string& path) {
    if (depth > kMaxDepth)
      refuse(node, "the document nests deeper than " + std::to_string(kMaxDepth) + " levels");
    if (++nodes > kMaxNodes)
      refuse(node, "the document expands to more than " + std::to_string(kMaxNodes) + " values");
    if (node.IsMap()) {
      visit_map(node, depth, path);
    } else if (node.IsSequence()) {
      std::size_t index = 0;
      for (const auto& element : node)
        visit(element, depth + 1, path + "[" + std::to_string(index++) + "]");
    }
  }
};

void reject_duplicate_keys(const YAML::Node& node, const std::string& file) {
  DocumentWalk{file}.visit(node, 0, "");
}

// Splits "a.b[2].c" into {"a", "b", "[2]", "c"}.
std::vector<std::string> split_path(const std::string& path) {
  std::vector<std::string> parts;
  std::string current;
  for (char c : path) {
    if (c == '.') {
      if (!current.empty()) parts.push_back(current);
      current.clear();
    } else if (c == '[') {
      if (!current.empty()) parts.push_back(current);
      current = "[";
    } else if (c == ']') {
      parts.push_back(current + "]");
      current.clear();
    } else {
      current += c;
    }
  }
  if (!current.empty()) parts.push_back(current);
  return parts;
}

// The path of the first `count` parts: {"a", "[2]", "b"} -> "a[2].b".
std::string joined(const std::vector<std::string>& parts, std::size_t count) {
  std::string path;
  for (std::size_t k = 0; k < count; ++k)
    path += (k == 0 || parts[k].front() == '[' ? "" : ".") + parts[k];
  return path;
}

// The element a path part "[2]" names in `node`, or throws.
std::size_t element_of(const YAML::Node& node, const std::string& part,
                       const SourceLocation& origin, const std::string& path) {
  std::size_t element = 0;
  const auto digits = std::string_view(part).substr(1, part.size() - 2);
  const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), element);
  if (error != std::errc() || end != digits.data() + digits.size() || !node.IsSequence() ||
      element >= node.size()) {
    throw ConfigError(origin, path, "index " + part + " does not name an existing element");
  }
  return element;
}

// Sets `value` at parts[index...] below `node`; the mappings it adds on the way are listed in
// `introduced` by their paths.
void assign_at(YAML::Node node, const std::vector<std::string>& parts, std::size_t index,
               const YAML::Node& value, const SourceLocation& origin, const std::string& path,
               std::vector<std::string>& introduced) {
  const std::string& part = parts[index];
  const bool last = index + 1 == parts.size();
  if (part.front() == '[') {
    const std::size_t element = element_of(node, part, origin, path);
    if (last) {
      node[element] = value;
    } else {
      assign_at(node[element], parts, index + 1, value, origin, path, introduced);
    }
    return;
  }
  if (!node.IsMap() && !node.IsNull()) {
    throw ConfigError(origin, path, "cannot set '" + part + "' inside " + node_kind(node));
  }
  if (last) {
    node[part] = value;
  } else {
    if (!node[part]) {
      node[part] = YAML::Node(YAML::NodeType::Map);
      introduced.push_back(joined(parts, index + 1));
    }
    assign_at(node[part], parts, index + 1, value, origin, path, introduced);
  }
}

// Removes the key or element at parts[index...] below `node` (--set path=null), or throws where
// there is none: a misspelt path must not pass for a removal.
void remove_at(YAML::Node node, const std::vector<std::string>& parts, std::size_t index,
               const SourceLocation& origin, const std::string& path) {
  const std::string& part = parts[index];
  const bool last = index + 1 == parts.size();
  std::string nothing = "there is nothing at '" + joined(parts, index + 1) + "' to remove";
  if (node.IsMap() && part.front() != '[') {
    std::vector<std::string> keys;
    for (const auto& entry : node)
      if (entry.first.IsScalar()) keys.push_back(entry.first.as<std::string>());
    if (const std::string near = closest_match(part, keys); !near.empty())
      nothing += " (did you mean '" + near + "'?)";
  }
  nothing += "; --set KEY=null removes a key or an element that is there";
  if (part.front() == '[') {
    const std::size_t element = element_of(node, part, origin, path);
    if (last) {
      node.remove(element);
    } else {
      remove_at(node[element], parts, index + 1, origin, path);
    }
    return;
  }
  if (!node.IsMap() || !node[part]) throw ConfigError(origin, path, nothing);
  if (last) {
    node.remove(part);
  } else {
    remove_at(node[part], parts, index + 1, origin, path);
  }
}

// Whether an override's value asks for a removal: YAML's null spelt out ("null", "~").
bool is_removal(const std::string& text, const YAML::Node& value) {
  const std::string spelt = trim(text);
  return value.IsNull() && (spelt == "null" || spelt == "Null" || spelt == "NULL" || spelt == "~");
}

}  // namespace

std::string expand_instance_path(const YAML::Node& root, const std::string& path,
                                 const std::vector<std::string>& instance_sections) {
  const std::string first = path.substr(0, path.find_first_of(".["));
  if (first.empty() || !root.IsMap() || root[first]) return path;
  std::string section;
  for (const auto& candidate : instance_sections) {
    const YAML::Node instances = root[candidate];
    if (!instances || !instances.IsMap() || !instances[first]) continue;
    if (!section.empty()) return path;  // two sections name it: leave the path as written
    section = candidate;
  }
  return section.empty() ? path : section + "." + path;
}

std::string read_text_file(const std::string& file) {
  std::ifstream stream(file);
  if (!stream) throw ConfigError({file, 0, 0, {}}, "", "cannot open the file for reading");
  std::stringstream buffer;
  buffer << stream.rdbuf();
  return buffer.str();
}

namespace {

// A text file holds no control bytes but tab, CR and LF: a NUL in a value used to read as an
// escape error, one in a comment passed unnoticed.
void reject_control_bytes(const std::string& text, const std::string& name) {
  int line = 1, column = 1;
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte < 0x20 && c != '\t' && c != '\r' && c != '\n') {
      throw ConfigError({name, line, column, {}}, "",
                        byte == 0 ? "the file holds a NUL byte (binary or corrupted?)"
                                  : "the file holds the control character " +
                                        printable(std::string(1, c)) + " (binary or corrupted?)");
    }
    if (c == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
}

// The YAML of `text`; a syntax error is located where yaml-cpp stopped, or, when it stopped
// because a flow collection or a quoted string was never closed, where that was opened.
YAML::Node parse_yaml(const std::string& text, const std::string& name) {
  try {
    return YAML::Load(text);
  } catch (const YAML::ParserException& error) {
    const int line = error.mark.line + 1, column = error.mark.column + 1;
    if (const auto unclosed = find_unclosed(text);
        unclosed && std::pair(unclosed->line, unclosed->column) <= std::pair(line, column)) {
      throw ConfigError({name, unclosed->line, unclosed->column, {}}, "",
                        "invalid YAML: " + unclosed->what);
    }
    throw ConfigError({name, line, column, {}}, "", "invalid YAML: " + error.msg);
  }
}

// Whether a quoted scalar of the document starts at (line, column), 1-based.
bool quoted_scalar_at(const YAML::Node& node, int line, int column) {
  if (node.IsScalar()) {
    const auto mark = node.Mark();
    return node.Tag() == "!" && mark.line + 1 == line && mark.column + 1 == column;
  }
  if (node.IsMap()) {
    for (const auto& entry : node) {
      if (quoted_scalar_at(entry.first, line, column) ||
          quoted_scalar_at(entry.second, line, column))
        return true;
    }
  } else if (node.IsSequence()) {
    for (const auto& element : node) {
      if (quoted_scalar_at(element, line, column)) return true;
    }
  }
  return false;
}

// yaml-cpp takes a single-quoted string left open to the end of the file for a string that holds
// the rest of the file (the error then was a missing key): refuse it where it opens. Call after
// reject_duplicate_keys, which bounds the walk.
void reject_quote_open_to_end(const YAML::Node& root, const std::string& text,
                              const std::string& name) {
  const auto unclosed = find_unclosed(text);
  if (!unclosed || !unclosed->to_end || !quoted_scalar_at(root, unclosed->line, unclosed->column))
    return;
  throw ConfigError({name, unclosed->line, unclosed->column, {}}, "",
                    "invalid YAML: " + unclosed->what);
}

// Applies one --set to the document.
void apply_override(ConfigDocument& document, const std::string& assignment,
                    const std::vector<std::string>& instance_sections) {
  const SourceLocation origin = command_line(document, assignment);
  const auto equals = assignment.find('=');
  if (equals == std::string::npos || equals == 0 || equals + 1 == assignment.size()) {
    throw ConfigError(origin, "", "expected --set key.path=value");
  }
  const std::string key = trim(assignment.substr(0, equals));
  // Names joined by single dots, each possibly indexed ("muscle.effects[0].stiffness").
  bool empty_name = key.empty() || key.front() == '.' || key.back() == '.' ||
                    key.find("..") != std::string::npos || key.front() == '[';
  if (empty_name) {
    throw ConfigError(origin, "",
                      "expected --set key.path=value, the key path names joined by '.' (e.g. "
                      "muscle.mechanics.k1); '" +
                          key + "' has an empty name");
  }
  const std::string path = expand_instance_path(document.root, key, instance_sections);
  YAML::Node value;
  try {
    value = YAML::Load(assignment.substr(equals + 1));
  } catch (const YAML::ParserException& error) {
    throw ConfigError(origin, path, "the value is not valid YAML: " + error.msg);
  }
  const std::string text = assignment.substr(equals + 1);
  if (is_removal(text, value)) {
    remove_at(document.root, split_path(path), 0, origin, path);
    document.overrides.push_back({path, assignment, value});
    return;
  }
  if (value.IsNull()) throw ConfigError(origin, path, "expected a value after '='");
  std::vector<std::string> introduced;
  assign_at(document.root, split_path(path), 0, value, origin, path, introduced);
  for (const auto& added : introduced) document.introduced.try_emplace(added, assignment);
  document.overrides.push_back({path, assignment, value});
}

std::shared_ptr<ConfigDocument> parse_document(const std::string& text, const std::string& name,
                                               const std::vector<std::string>& overrides,
                                               std::shared_ptr<const UnitSystem> units,
                                               const std::vector<std::string>& instance_sections,
                                               const std::string& override_origin) {
  auto document = std::make_shared<ConfigDocument>();
  document->file = name;
  document->override_origin = override_origin;
  document->units = std::move(units);
  reject_control_bytes(text, name);
  document->root = parse_yaml(text, name);
  if (document->root.IsNull()) {
    document->empty = true;
    document->root = YAML::Node(YAML::NodeType::Map);
  }
  if (!document->root.IsMap()) {
    const auto mark = document->root.Mark();
    throw ConfigError(
        {name, mark.line + 1, mark.column + 1, {}}, "",
        "expected a mapping of sections at the top level, got " + node_kind(document->root));
  }
  reject_duplicate_keys(document->root, name);
  reject_quote_open_to_end(document->root, text, name);
  for (const auto& assignment : overrides) apply_override(*document, assignment, instance_sections);
  document->resolved = YAML::Clone(document->root);
  return document;
}

}  // namespace

ConfigNode ConfigNode::load_text(const std::string& text, const std::string& name,
                                 const std::vector<std::string>& overrides,
                                 std::shared_ptr<const UnitSystem> units,
                                 const std::vector<std::string>& instance_sections,
                                 const std::string& override_origin) {
  return ConfigNode(
      parse_document(text, name, overrides, std::move(units), instance_sections, override_origin),
      {}, "");
}

ConfigNode ConfigNode::load_file(const std::string& file, const std::vector<std::string>& overrides,
                                 std::shared_ptr<const UnitSystem> units,
                                 const std::vector<std::string>& instance_sections,
                                 const std::string& override_origin) {
  return load_text(read_text_file(file), file, overrides, std::move(units), instance_sections,
                   override_origin);
}

const std::vector<Assignment>& ConfigNode::assignments() const {
  return document_->overrides;
}

ConfigNode::ConfigNode(std::shared_ptr<ConfigDocument> document, YAML::Node node, std::string path)
    : document_(std::move(document)), node_(std::move(node)), path_(std::move(path)) {
  if (path_.empty()) node_.reset(document_->root);
}

ConfigNode ConfigNode::child(const YAML::Node& node, std::string path) const {
  return ConfigNode(document_, node, std::move(path));
}

std::string ConfigNode::child_path(std::string_view key) const {
  return join(path_, key);
}

const UnitSystem& ConfigNode::units() const {
  return *document_->units;
}

SourceLocation ConfigNode::location() const {
  if ((node_.IsMap() || node_.IsSequence()) && node_.Style() == YAML::EmitterStyle::Block &&
      parent_.IsMap()) {
    for (const auto& entry : parent_)
      if (entry.first.IsScalar() && entry.first.Scalar() == key_)
        return locate(*document_, path_, entry.first.Mark());
  }
  return locate(*document_, path_, node_.Mark());
}

std::string ConfigNode::parameter_path() const {
  return parameter_path_of(path_);
}

std::string ConfigNode::parameter_path_of(const std::string& path) const {
  // The longest renamed prefix of the path, found by trying each shorter prefix in turn.
  const auto& prefixes = document_->parameter_prefixes;
  if (!prefixes.empty()) {
    for (std::size_t end = path.size(); end > 0; --end) {
      if (end < path.size() && path[end] != '.' && path[end] != '[') continue;
      const auto found = prefixes.find(path.substr(0, end));
      if (found != prefixes.end()) return found->second + path.substr(end);
    }
  }
  return path;
}

std::string ConfigNode::parameter_path(std::string_view key) const {
  return join(parameter_path(), key);
}

void ConfigNode::name_parameters(const std::string& prefix) const {
  document_->parameter_prefixes[path_] = prefix;
}

void ConfigNode::fail(const std::string& problem) const {
  throw ConfigError(location(), path_, problem);
}

bool ConfigNode::has(std::string_view key) const {
  document_->read(child_path(key)).optional = true;
  return present(key);
}

bool ConfigNode::present(std::string_view key) const {
  document_->known_keys[path_].insert(std::string(key));
  const YAML::Node& node = node_;  // const access never inserts
  return node.IsMap() && node[std::string(key)].IsDefined();
}

void ConfigNode::declare(std::initializer_list<std::string_view> keys) const {
  auto& known = document_->known_keys[path_];
  for (const auto key : keys) known.insert(std::string(key));
}

void ConfigNode::fail_missing(std::string_view key) const {
  // A file without a document misses every section: say that instead.
  if (path_.empty() && document_->empty) fail_empty_file(key);
  // A misspelt key is the usual reason a required one is missing: point at it.
  if (node_.IsMap()) {
    std::vector<std::string> expected{std::string(key)};
    for (const auto& entry : node_) {
      const std::string present = entry.first.as<std::string>();
      if (document_->consumed.count(join(path_, present))) continue;
      if (document_->known_keys[path_].count(present)) continue;  // a legitimate other key
      if (!closest_match(present, expected).empty()) {
        throw ConfigError(
            locate(*document_, join(path_, present), entry.first.Mark()), join(path_, present),
            "unknown key '" + present + "' (did you mean '" + std::string(key) + "'?)");
      }
    }
  }
  // A --set KEY=null removed it: that --set is where to look.
  const std::string removed = child_path(key);
  for (auto assignment = document_->overrides.rbegin(); assignment != document_->overrides.rend();
       ++assignment) {
    if (assignment->value.IsNull() && assignment->path == removed)
      throw ConfigError(command_line(*document_, assignment->text), path_,
                        "missing required key '" + std::string(key) + "' (this --set removed it)");
  }
  fail("missing required key '" + std::string(key) + "'");
}

void ConfigNode::fail_empty_file(std::string_view key) const {
  std::string others;
  for (const auto& section : document_->known_keys[path_]) {
    if (section != key) others += (others.empty() ? "" : ", ") + section;
  }
  throw ConfigError({document_->file, 1, 1, {}}, "",
                    "the file is empty (or holds only comments); expected a mapping with '" +
                        std::string(key) + "'" +
                        (others.empty() ? "" : " and any of its other sections (" + others + ")"));
}

ConfigNode ConfigNode::at(std::string_view key) const {
  if (!node_.IsMap())
    fail("expected a mapping with key '" + std::string(key) + "', got " + node_kind(node_));
  if (!present(key)) fail_missing(key);
  const std::string path = child_path(key);
  document_->consumed.insert(path);
  const YAML::Node& node = node_;
  ConfigNode found = child(node[std::string(key)], path);
  found.parent_.reset(node_);  // rebinds the handle (operator= would assign the value)
  found.key_ = key;
  return found;
}

std::optional<ConfigNode> ConfigNode::find(std::string_view key) const {
  if (!node_.IsMap()) {
    if (node_.IsNull()) return std::nullopt;
    fail("expected a mapping, got " + node_kind(node_));
  }
  if (!has(key)) return std::nullopt;
  return at(key);
}

std::vector<ConfigNode> ConfigNode::elements() const {
  if (!node_.IsSequence()) fail("expected a sequence (a YAML list), got " + node_kind(node_));
  std::vector<ConfigNode> result;
  for (std::size_t i = 0; i < node_.size(); ++i) {
    const std::string path = path_ + "[" + std::to_string(i) + "]";
    document_->consumed.insert(path);
    const YAML::Node& node = node_;
    result.push_back(child(node[i], path));
  }
  return result;
}

std::vector<std::pair<std::string, ConfigNode>> ConfigNode::entries() const {
  if (!node_.IsMap()) fail("expected a mapping, got " + node_kind(node_));
  std::vector<std::pair<std::string, ConfigNode>> result;
  for (const auto& entry : node_) {
    const std::string key = entry.first.as<std::string>();
    result.emplace_back(key, at(key));
  }
  return result;
}

double ConfigNode::as_quantity(std::string_view si_unit, const ValueCheck& check) const {
  return read_quantity(si_unit, check, false);
}

double ConfigNode::as_difference(std::string_view si_unit, const ValueCheck& check) const {
  return read_quantity(si_unit, check, true);
}

double ConfigNode::read_quantity(std::string_view si_unit, const ValueCheck& check,
                                 bool difference) const {
  document_->log(path_, quantity_text(si_unit), check);
  const bool dimensionless = si_unit == "1";
  const std::string wanted =
      dimensionless ? "a dimensionless number" : "a quantity in " + std::string(si_unit);
  if (!node_.IsScalar()) fail("expected " + wanted + ", got " + node_kind(node_));
  const std::string text = node_.Scalar();
  const std::string trimmed = trim(text);
  double value = 0.0;
  const char* begin = trimmed.data();
  const char* end = begin + trimmed.size();
  if (begin != end && *begin == '+') ++begin;
  const auto [rest, error] = std::from_chars(begin, end, value);
  if (error != std::errc() || trimmed.empty()) {
    fail("expected " + wanted +
         (dimensionless ? "" : " such as '1.5 " + std::string(si_unit) + "'") + ", got '" + text +
         "'");
  }
  const std::string unit = trim(std::string_view(rest, static_cast<std::size_t>(end - rest)));
  // What the key measures with units a user would write, never the number in the SI unit: a
  // bare number may be meant in another unit (N/mm for N/m) and be 1000 times off.
  if (unit.empty() && !dimensionless) {
    const std::string dimension = units().describe_dimension(si_unit);
    fail("'" + text + "' has no unit; expected " +
         (dimension.empty()
              ? "a quantity in " + std::string(si_unit) + " (or a unit convertible to it)"
              : dimension));
  }
  if (!unit.empty()) {
    try {
      value = difference ? units().convert_difference(value, unit, si_unit)
                         : units().convert(value, unit, si_unit);
    } catch (const UnitError& problem) {
      const std::string dimension = dimensionless ? "" : units().describe_dimension(si_unit);
      fail("wrong unit in '" + text + "': " + problem.what() +
           (dimensionless       ? " (expected a dimensionless number)"
            : dimension.empty() ? ""
                                : "; expected " + dimension));
    }
  }
  if (std::string problem = check.problem(value, si_unit, "'" + text + "'"); !problem.empty())
    fail(problem);
  if (std::string doubt = check.implausibility(value, si_unit, "'" + text + "'"); !doubt.empty())
    document_->warnings.push_back(
        printable(location().describe() + ": warning: " + path_ + ": " + doubt));
  return value;
}

const std::vector<std::string>& ConfigNode::warnings() const {
  return document_->warnings;
}

double ConfigNode::as_number(const ValueCheck& check) const {
  return as_quantity("1", check);
}

long ConfigNode::as_integer(const ValueCheck& check) const {
  document_->log(path_, "integer", check);
  if (!node_.IsScalar()) fail("expected an integer, got " + node_kind(node_));
  const std::string text = trim(node_.Scalar());
  long value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size()) {
    fail("expected an integer, got '" + node_.Scalar() + "'");
  }
  if (!check.accepts(static_cast<double>(value))) {
    fail("expected an integer, " + check.expectation() + ", got '" + node_.Scalar() + "'");
  }
  return value;
}

bool ConfigNode::as_bool() const {
  document_->log(path_, "true or false");
  bool value = false;
  if (!node_.IsScalar() || !YAML::convert<bool>::decode(node_, value)) {
    fail("expected true or false, got " +
         (node_.IsScalar() ? "'" + node_.Scalar() + "'" : node_kind(node_)));
  }
  return value;
}

std::string ConfigNode::as_text() const {
  document_->log(path_, "text");
  if (!node_.IsScalar()) fail("expected a text value, got " + node_kind(node_));
  return node_.Scalar();
}

std::string ConfigNode::as_choice(std::initializer_list<std::string_view> options) const {
  return as_choice(std::vector<std::string>(options.begin(), options.end()));
}

std::string ConfigNode::as_choice(const std::vector<std::string>& candidates) const {
  const std::string value = as_text();
  std::string options;
  for (const auto& option : candidates) options += (options.empty() ? "" : ", ") + option;
  document_->log(path_, "one of " + options);
  if (std::find(candidates.begin(), candidates.end(), value) != candidates.end()) return value;
  std::string listed;
  for (const auto& option : candidates) listed += (listed.empty() ? "" : ", ") + option;
  const std::string suggestion = closest_match(value, candidates);
  fail("expected one of " + listed + ", got '" + value + "'" +
       (suggestion.empty() ? "" : " (did you mean '" + suggestion + "'?)"));
}

double ConfigNode::quantity(std::string_view key, std::string_view si_unit,
                            const ValueCheck& check) const {
  return at(key).as_quantity(si_unit, check);
}

void ConfigNode::record_default(std::string_view key, const std::string& value) const {
  // Mirror the path into the resolved document, creating mappings on the way.
  std::vector<std::string> parts = split_path(path_);
  YAML::Node node = document_->resolved;
  for (const auto& part : parts) {
    YAML::Node next;
    if (part.front() == '[') {
      next.reset(node[std::stoul(part.substr(1, part.size() - 2))]);
    } else {
      if (!node[part]) node[part] = YAML::Node(YAML::NodeType::Map);
      next.reset(node[part]);
    }
    node.reset(next);
  }
  node[std::string(key)] = value;
}

double ConfigNode::quantity_or(std::string_view key, std::string_view si_unit, double fallback,
                               const ValueCheck& check) const {
  return read_quantity_or(key, si_unit, fallback, check, false);
}

double ConfigNode::difference(std::string_view key, std::string_view si_unit,
                              const ValueCheck& check) const {
  return at(key).as_difference(si_unit, check);
}

double ConfigNode::difference_or(std::string_view key, std::string_view si_unit, double fallback,
                                 const ValueCheck& check) const {
  return read_quantity_or(key, si_unit, fallback, check, true);
}

double ConfigNode::read_quantity_or(std::string_view key, std::string_view si_unit, double fallback,
                                    const ValueCheck& check, bool difference) const {
  const std::string stated =
      number_text(fallback) + (si_unit == "1" ? "" : " " + std::string(si_unit));
  document_->log(child_path(key), quantity_text(si_unit), check);
  document_->read(child_path(key)).fallback = stated;
  if (auto value = find(key)) return value->read_quantity(si_unit, check, difference);
  record_default(key, stated);
  return fallback;
}

double ConfigNode::number(std::string_view key, const ValueCheck& check) const {
  return at(key).as_number(check);
}

double ConfigNode::number_or(std::string_view key, double fallback, const ValueCheck& check) const {
  return quantity_or(key, "1", fallback, check);
}

long ConfigNode::integer(std::string_view key, const ValueCheck& check) const {
  return at(key).as_integer(check);
}

long ConfigNode::integer_or(std::string_view key, long fallback, const ValueCheck& check) const {
  document_->log(child_path(key), "integer", check);
  document_->read(child_path(key)).fallback = std::to_string(fallback);
  if (auto value = find(key)) return value->as_integer(check);
  record_default(key, std::to_string(fallback));
  return fallback;
}

bool ConfigNode::boolean_or(std::string_view key, bool fallback) const {
  document_->log(child_path(key), "true or false");
  document_->read(child_path(key)).fallback = fallback ? "true" : "false";
  if (auto value = find(key)) return value->as_bool();
  record_default(key, fallback ? "true" : "false");
  return fallback;
}

std::string ConfigNode::text(std::string_view key) const {
  return at(key).as_text();
}

std::string ConfigNode::choice(std::string_view key,
                               std::initializer_list<std::string_view> options) const {
  return at(key).as_choice(options);
}

std::string ConfigNode::choice(std::string_view key,
                               const std::vector<std::string>& options) const {
  return at(key).as_choice(options);
}

std::string ConfigNode::choice_or(std::string_view key,
                                  std::initializer_list<std::string_view> options,
                                  std::string_view fallback) const {
  return choice_or(key, std::vector<std::string>(options.begin(), options.end()), fallback);
}

std::string ConfigNode::choice_or(std::string_view key, const std::vector<std::string>& options,
                                  std::string_view fallback) const {
  std::string listed;
  for (const auto& option : options) listed += (listed.empty() ? "" : ", ") + option;
  document_->log(child_path(key), "one of " + listed);
  document_->read(child_path(key)).fallback = std::string(fallback);
  if (auto value = find(key)) return value->as_choice(options);
  record_default(key, std::string(fallback));
  return std::string(fallback);
}

std::pair<double, double> ConfigNode::interval(std::string_view key, std::string_view si_unit,
                                               const ValueCheck& check) const {
  const ConfigNode node = at(key);
  const auto bounds = node.elements();
  if (bounds.size() != 2)
    node.fail("expected [lower, upper], got " + std::to_string(bounds.size()) + " values");
  const double lower = bounds[0].as_quantity(si_unit, check);
  const double upper = bounds[1].as_quantity(si_unit, check);
  if (!(lower < upper)) node.fail("expected lower < upper");
  return {lower, upper};
}

namespace {

std::string listed(const std::vector<std::string>& names, const std::string& separator = ", ") {
  std::string text;
  for (const auto& name : names) text += (text.empty() ? "" : separator) + name;
  return text;
}

// The first key of the document that nobody asked for, explained: a key that another variant of
// its section takes (a hanging mass's 'mass' under a load of type deflection) is named as such,
// and a misspelling gets the nearest key that this section takes.
class UnknownKeys {
 public:
  UnknownKeys(const ConfigDocument& document, const VariantKeys& variant_keys)
      : document_(document), variant_keys_(variant_keys) {}

  void visit(const YAML::Node& node, const std::string& path) const {
    if (node.IsMap()) {
      for (const auto& entry : node) {
        const std::string key = entry.first.as<std::string>();
        const std::string child = join(path, key);
        if (!document_.consumed.count(child)) {
          throw ConfigError(locate(document_, child, entry.first.Mark()), child,
                            problem(path, key));
        }
        visit(entry.second, child);
      }
    } else if (node.IsSequence()) {
      for (std::size_t i = 0; i < node.size(); ++i)
        visit(node[i], path + "[" + std::to_string(i) + "]");
    }
  }

 private:
  std::string problem(const std::string& path, const std::string& key) const {
    std::vector<std::string> candidates;
    if (const auto known = document_.known_keys.find(path); known != document_.known_keys.end())
      candidates.assign(known->second.begin(), known->second.end());
    if (const auto variant = document_.variants.find(path);
        variant != document_.variants.end() && variant_keys_) {
      if (std::string other = of_another_variant(variant->second, key, candidates); !other.empty())
        return other;
    }
    if (std::find(candidates.begin(), candidates.end(), key) != candidates.end())
      return "'" + key + "' is not used with the other settings of this section";
    std::string problem = "unknown key '" + key + "'";
    if (const std::string suggestion = closest_match(key, candidates); !suggestion.empty()) {
      problem += " (did you mean '" + suggestion + "'?)";
    } else if (!candidates.empty()) {
      problem += "; known keys here: " + listed(candidates);
    }
    return problem;
  }

  // The message for a key that only other kinds of the section's category take, or empty; the
  // candidates lose the keys of other kinds that this one does not take.
  std::string of_another_variant(const Variant& variant, const std::string& key,
                                 std::vector<std::string>& candidates) const {
    const auto keys = variant_keys_(variant.category);
    const auto own = keys.find(variant.kind);
    if (own == keys.end() || own->second.empty()) return {};
    const auto takes = [&](const std::string& name) {
      return name == variant.selector || own->second.count(name) > 0;
    };
    const auto kinds_taking = [&](const std::string& name) {
      std::vector<std::string> kinds;
      for (const auto& [kind, names] : keys) {
        if (kind != variant.kind && names.count(name)) kinds.push_back(kind);
      }
      return kinds;
    };
    std::erase_if(candidates, [&](const std::string& candidate) {
      return !takes(candidate) && !kinds_taking(candidate).empty();
    });
    const auto users = kinds_taking(key);
    if (takes(key) || users.empty()) return {};
    std::vector<std::string> own_keys(own->second.begin(), own->second.end());
    std::erase(own_keys, variant.selector);
    const std::string chosen = variant.selector + ": " + variant.kind;
    return "'" + key + "' is not used with " + chosen + "; it belongs to " + variant.selector +
           ": " + listed(users, " or ") + " (" + chosen + " takes " + listed(own_keys) + ")";
  }

  const ConfigDocument& document_;
  const VariantKeys& variant_keys_;
};

}  // namespace

std::vector<KeyRead> ConfigNode::reads() const {
  return document_->reads;
}

void ConfigNode::mark_part(const std::string& what) const {
  KeyRead& entry = document_->read(path_);
  if (entry.part) return;  // the outermost description stands
  entry.expected = what;
  entry.part = true;
}

void ConfigNode::describe_key(std::string_view key, const std::string& expected,
                              const std::string& fallback) const {
  KeyRead& entry = document_->read(child_path(key));
  entry.expected = expected;
  if (!fallback.empty()) entry.fallback = fallback;
}

void ConfigNode::reject_unknown_keys(const VariantKeys& variant_keys) const {
  UnknownKeys(*document_, variant_keys).visit(document_->root, "");
}

void ConfigNode::mark_variant(const std::string& category, const std::string& selector,
                              const std::string& kind) const {
  document_->variants[path_] = {category, selector, kind};
}

std::shared_ptr<const UnitSystem> ConfigNode::shared_units() const {
  return document_->units;
}

std::string ConfigNode::resolved_yaml() const {
  YAML::Emitter emitter;
  emitter << document_->resolved;
  return emitter.c_str();
}

std::string file_named_by(const ConfigNode& node) {
  const std::filesystem::path file(node.as_text());
  const SourceLocation location = node.location();
  if (file.is_absolute() || !location.origin.empty() || location.file.empty()) return file;
  return (std::filesystem::path(location.file).parent_path() / file).string();
}

}  // namespace tcpmsim
