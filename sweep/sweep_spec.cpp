#include "sweep/sweep_spec.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>

#include "kinds/standard_kinds.h"
#include "sim/random_stream.h"
#include "sweep/sweep_design.h"

namespace tcpmsim::sweep {

void blame_set(const ConfigNode& root, const std::string& scenario, const ConfigError& error) {
  const auto set = root.find("set");
  if (!set) return;
  const std::string problem = "scenario '" + scenario + "' does not take it: " +
                              (error.key_path().empty() ? "" : error.key_path() + ": ") +
                              error.problem();
  for (const auto& element : set->elements()) {
    if (!error.location().origin.empty() &&
        error.location().origin.find(element.as_text()) != std::string::npos)
      element.fail(problem);
  }
  if (error.location().line == 0) set->fail(problem);
}

std::vector<std::string> read_set(const ConfigNode& root) {
  std::vector<std::string> overrides;
  if (const auto set = root.find("set")) {
    for (const auto& element : set->elements()) overrides.push_back(element.as_text());
  }
  return overrides;
}

namespace {

// One axis as read: its values, or the indices of its texts for a structural axis.
struct AxisValues {
  Axis axis;
  std::vector<double> values;
};

std::vector<SweepScenario> read_scenarios(const ConfigNode& root, const std::string& file,
                                          const std::vector<std::string>& overrides,
                                          const std::shared_ptr<const UnitSystem>& units) {
  const auto directory = std::filesystem::path(file).parent_path();
  std::vector<std::pair<std::string, ConfigNode>> named;
  if (root.has("scenarios")) {
    if (root.has("scenario")) root.at("scenario").fail("give 'scenario' or 'scenarios', not both");
    named = root.at("scenarios").entries();
    if (named.empty()) root.at("scenarios").fail("expected at least one named scenario file");
  } else {
    named.emplace_back("scenario", root.at("scenario"));
  }
  std::vector<SweepScenario> scenarios;
  for (const auto& [name, node] : named) {
    // The name is a group of the output (/runs/<run>/<name>), so one HDF5 path element.
    if (name.empty() || name == "." || name == ".." || name.find('/') != std::string::npos)
      node.fail("the scenario's name '" + name +
                "' names its traces' group in the output: expected a name without '/', and not "
                "'', '.' or '..'");
    const auto path = (directory / node.as_text()).lexically_normal().string();
    if (!std::filesystem::is_regular_file(path)) node.fail("no scenario file '" + path + "'");
    SweepScenario entry{name, path, overrides, nullptr};
    try {
      entry.scenario = std::make_shared<const Scenario>(load_scenario(path, overrides, units));
    } catch (const ConfigError& error) {
      blame_set(root, name, error);
      throw;
    }
    scenarios.push_back(std::move(entry));
  }
  return scenarios;
}

// The declaration of `path` in the scenarios that have it (nullptr in those that do not).
const ParameterInfo* find_parameter(const SweepScenario& scenario, const std::string& path) {
  const auto index = scenario.scenario->system->parameter_index(path);
  if (!index) return nullptr;
  return &scenario.scenario->system->parameters()[static_cast<std::size_t>(*index)];
}

// The SI unit of a settable parameter that at least one scenario has; fails at `node` if none
// has it, if it is derived, or if the scenarios disagree on its unit.
std::string parameter_unit(const std::vector<SweepScenario>& scenarios, const std::string& path,
                           const ConfigNode& node) {
  std::string unit;
  for (const auto& scenario : scenarios) {
    const ParameterInfo* parameter = find_parameter(scenario, path);
    if (parameter == nullptr) continue;
    if (!parameter->derived_from.empty())
      node.fail("'" + path + "' is derived (" + parameter->derived_from +
                "): sweep what it is derived from");
    if (!unit.empty() && unit != parameter->declaration.unit)
      node.fail("'" + path + "' has different units in the scenarios");
    unit = parameter->declaration.unit;
  }
  return unit;
}

// The parameter of the scenarios whose path is nearest to `path` (a misspelling), or "".
std::string nearest_parameter(const std::vector<SweepScenario>& scenarios,
                              const std::string& path) {
  std::vector<std::string> paths;
  for (const auto& scenario : scenarios)
    for (const auto& parameter : scenario.scenario->system->parameters())
      paths.push_back(parameter.declaration.path);
  return closest_match(path, paths);
}

bool is_parameter(const std::vector<SweepScenario>& scenarios, const std::string& path) {
  for (const auto& scenario : scenarios)
    if (find_parameter(scenario, path) != nullptr) return true;
  return false;
}

Spacing read_spacing(const ConfigNode& node) {
  return node.choice_or("spacing", {"linear", "log"}, "linear") == "log" ? Spacing::logarithmic
                                                                         : Spacing::linear;
}

// A range's ends, in `unit` (a plain number for a structural axis), checked for log spacing.
std::pair<double, double> read_ends(const ConfigNode& node, const std::string& unit,
                                    Spacing spacing) {
  const auto read = [&](std::string_view key) {
    return unit.empty() ? node.number(key) : node.quantity(key, unit);
  };
  const double from = read("from");
  const double to = read("to");
  if (spacing == Spacing::logarithmic && !(from * to > 0.0))
    node.at("to").fail("a log range needs ends of one sign, neither zero");
  return {from, to};
}

// At most a million values an axis: the runs are held in memory.
int read_count(const ConfigNode& node) {
  return static_cast<int>(node.integer("count", ValueCheck::between(1, 1e6)));
}

std::vector<double> read_axis_values(const ConfigNode& node, const Axis& axis, std::uint64_t seed,
                                     std::vector<std::string>& texts) {
  node.declare({"parameter", "values", "range", "latin_hypercube", "random"});
  const int forms =
      node.has("values") + node.has("range") + node.has("latin_hypercube") + node.has("random");
  if (forms != 1)
    node.fail("expected exactly one of 'values', 'range', 'latin_hypercube' or 'random'");
  const std::string& unit = axis.unit;
  RandomStream stream(seed, "sweep axis " + axis.path);
  std::vector<double> values;
  if (const auto list = node.find("values")) {
    const auto elements = list->elements();
    if (elements.empty()) list->fail("an empty list of values");
    for (const auto& element : elements) {
      if (axis.structural) {
        texts.push_back(element.as_text());
        values.push_back(std::nan(""));
      } else {
        values.push_back(element.as_quantity(unit));
      }
    }
    return values;
  }
  if (const auto range = node.find("range")) {
    const Spacing spacing = read_spacing(*range);
    const auto [from, to] = read_ends(*range, unit, spacing);
    values = spaced_values(from, to, read_count(*range), spacing);
  } else if (const auto lhs = node.find("latin_hypercube")) {
    const Spacing spacing = read_spacing(*lhs);
    const auto [from, to] = read_ends(*lhs, unit, spacing);
    values = latin_hypercube_values(from, to, read_count(*lhs), spacing, stream);
  } else {
    const ConfigNode random = node.at("random");
    const std::string distribution =
        random.choice("distribution", {"uniform", "log_uniform", "normal"});
    if (distribution == "normal") {
      const double mean = unit.empty() ? random.number("mean") : random.quantity("mean", unit);
      const double deviation =
          unit.empty() ? random.number("standard_deviation", ValueCheck::non_negative())
                       : random.difference("standard_deviation", unit, ValueCheck::non_negative());
      values = normal_values(mean, deviation, read_count(random), stream);
    } else {
      const Spacing spacing =
          distribution == "log_uniform" ? Spacing::logarithmic : Spacing::linear;
      const auto [from, to] = read_ends(random, unit, spacing);
      values = uniform_values(from, to, read_count(random), spacing, stream);
    }
  }
  if (axis.structural) {
    for (double value : values) texts.push_back(number_text(value, 17));
  }
  return values;
}

void check_structural_value(const ConfigNode& node, const Axis& axis, const SweepScenario& scenario,
                            const std::string& text,
                            const std::shared_ptr<const UnitSystem>& units) {
  auto overrides = scenario.overrides;
  overrides.push_back(axis.path + "=" + text);
  try {
    load_scenario(scenario.file, overrides, units);
  } catch (const ConfigError& error) {
    node.fail("'" + axis.path + "' is not a parameter of scenario '" + scenario.name +
              "' (tcpmsim validate lists them), and setting it to '" + text +
              "' as a key fails: " + error.problem());
  }
}

// Checks that every scenario takes each of a structural axis' values, before any run.
void check_structural(const ConfigNode& node, const Axis& axis,
                      const std::vector<SweepScenario>& scenarios,
                      const std::shared_ptr<const UnitSystem>& units) {
  const std::set<std::string> distinct(axis.texts.begin(), axis.texts.end());
  for (const auto& scenario : scenarios) {
    for (const auto& text : distinct) check_structural_value(node, axis, scenario, text, units);
  }
}

AxisValues read_axis(const ConfigNode& node, const std::vector<SweepScenario>& scenarios,
                     std::uint64_t seed, const std::shared_ptr<const UnitSystem>& units) {
  AxisValues read;
  Axis& axis = read.axis;
  const ConfigNode parameter = node.at("parameter");
  axis.path = parameter.as_text();
  axis.structural = !is_parameter(scenarios, axis.path);
  if (!axis.structural) axis.unit = parameter_unit(scenarios, axis.path, parameter);
  std::vector<std::string> texts;
  try {
    read.values = read_axis_values(node, axis, seed, texts);
  } catch (const ConfigError&) {
    // A path no scenario has is read as a structural axis of plain numbers, so a misspelt
    // parameter's range fails on its units ("cannot be converted to '1'"): the path is the
    // mistake, and it is reported at `parameter:`.
    const std::string nearest = axis.structural ? nearest_parameter(scenarios, axis.path) : "";
    if (!nearest.empty())
      parameter.fail("unknown parameter '" + axis.path + "' (did you mean '" + nearest +
                     "'? tcpmsim validate lists the parameters)");
    throw;
  }
  axis.texts = std::move(texts);
  if (axis.structural) check_structural(parameter, axis, scenarios, units);
  return read;
}

// The axes and their runs: a grid over the entries of `axes` (an axis, or `zip: [axes]`), or
// every axis zipped.
void read_axes(const ConfigNode& root, const std::vector<SweepScenario>& scenarios,
               const std::shared_ptr<const UnitSystem>& units, SweepSpec& spec) {
  const bool zipped = root.choice_or("combine", {"grid", "zip"}, "grid") == "zip";
  std::vector<AxisGroup> groups;
  std::vector<AxisValues> axes;
  const auto add = [&](const ConfigNode& node, AxisGroup& group) {
    axes.push_back(read_axis(node, scenarios, spec.seed, units));
    for (const auto& earlier : axes) {
      if (&earlier != &axes.back() && earlier.axis.path == axes.back().axis.path)
        node.at("parameter").fail("'" + earlier.axis.path + "' is swept twice");
    }
    std::vector<double> indices(axes.back().values.size());
    for (std::size_t k = 0; k < indices.size(); ++k) indices[k] = static_cast<double>(k);
    if (!group.empty() && group.front().size() != indices.size())
      node.fail("zipped axes must have equal lengths: this one has " +
                std::to_string(indices.size()) + " values, the first " +
                std::to_string(group.front().size()));
    group.push_back(std::move(indices));
  };
  if (const auto list = root.find("axes")) {
    AxisGroup all;
    for (const auto& entry : list->elements()) {
      AxisGroup group;
      if (entry.has("zip")) {
        entry.declare({"zip"});
        for (const auto& member : entry.at("zip").elements()) add(member, zipped ? all : group);
      } else {
        add(entry, zipped ? all : group);
      }
      if (!zipped) groups.push_back(std::move(group));
    }
    if (zipped) groups.push_back(std::move(all));
  }
  if (const std::string problem = grid_size_problem(groups); !problem.empty())
    root.at("axes").fail(problem);
  for (auto& indices : grid_runs(groups)) {
    std::vector<double> run;
    for (std::size_t a = 0; a < axes.size(); ++a)
      run.push_back(axes[a].values[static_cast<std::size_t>(indices[a])]);
    spec.runs.push_back(std::move(run));
    // A structural axis' texts follow the runs.
  }
  std::vector<std::vector<std::string>> texts_by_run(axes.size());
  for (const auto& indices : grid_runs(groups)) {
    for (std::size_t a = 0; a < axes.size(); ++a) {
      if (axes[a].axis.structural)
        texts_by_run[a].push_back(axes[a].axis.texts[static_cast<std::size_t>(indices[a])]);
    }
  }
  for (std::size_t a = 0; a < axes.size(); ++a) {
    if (axes[a].axis.structural) axes[a].axis.texts = std::move(texts_by_run[a]);
    spec.axes.push_back(std::move(axes[a].axis));
  }
}

std::vector<std::string> read_paths(const ConfigNode& node, std::string_view key,
                                    const std::vector<SweepScenario>& scenarios,
                                    std::vector<std::string>& units) {
  std::vector<std::string> paths;
  if (const auto list = node.find(key)) {
    for (const auto& element : list->elements()) {
      const std::string path = element.as_text();
      if (!is_parameter(scenarios, path))
        element.fail("'" + path +
                     "' is not a parameter of any scenario (tcpmsim validate lists them)");
      units.push_back(parameter_unit(scenarios, path, element));
      paths.push_back(path);
    }
  }
  return paths;
}

// (u1)*(u2)/((u3)*(u4)) as udunits reads it.
std::string product_unit(const std::vector<std::string>& multiply,
                         const std::vector<std::string>& divide) {
  std::string text = "1";
  for (const auto& unit : multiply) text += "*(" + unit + ")";
  for (const auto& unit : divide) text += "/(" + unit + ")";
  return text;
}

DerivedParameter read_derived(const ConfigNode& node, const std::vector<SweepScenario>& scenarios,
                              const UnitSystem& units) {
  DerivedParameter derived;
  const ConfigNode parameter = node.at("parameter");
  derived.path = parameter.as_text();
  if (!is_parameter(scenarios, derived.path))
    parameter.fail("'" + derived.path +
                   "' is not a parameter of any scenario (tcpmsim validate lists them)");
  derived.unit = parameter_unit(scenarios, derived.path, parameter);
  std::vector<std::string> multiply_units, divide_units;
  derived.multiply = read_paths(node, "multiply", scenarios, multiply_units);
  derived.divide = read_paths(node, "divide", scenarios, divide_units);
  if (derived.multiply.empty() && derived.divide.empty())
    node.fail("expected 'multiply' or 'divide': the parameters it is derived from");
  derived.factor = node.number_or("factor", 1.0);
  const std::string unit = product_unit(multiply_units, divide_units);
  if (!units.convertible(unit, derived.unit) ||
      std::abs(units.convert(1.0, unit, derived.unit) - 1.0) > 1e-12)
    node.fail("the product has the unit " + unit + ", but '" + derived.path + "' is in " +
              derived.unit);
  return derived;
}

void read_store(const ConfigNode& root, SweepSpec& spec) {
  const auto store = root.find("store");
  if (!store) return;
  const std::string traces = store->choice_or("traces", {"none", "decimated", "full"}, "none");
  spec.traces = traces == "full"        ? TraceStorage::full
                : traces == "decimated" ? TraceStorage::decimated
                                        : TraceStorage::none;
  if (spec.traces != TraceStorage::decimated) {
    // An interval left from a decimated store that a --set changed: say how to replace the
    // whole section, since a --set cannot remove a key.
    if (store->has("interval"))
      store->at("interval")
          .fail("applies to traces: decimated only (traces here: " + traces +
                "); give the store without it, e.g. --set 'store={traces: " + traces + "}'");
    return;
  }
  spec.trace_interval = store->quantity("interval", "s", ValueCheck::positive());
  for (const auto& scenario : spec.scenarios) {
    if (decimation_stride(spec.trace_interval, scenario.scenario->settings.output_interval) == 0)
      store->at("interval")
          .fail("must be a multiple of scenario '" + scenario.name + "''s output interval (" +
                number_text(scenario.scenario->settings.output_interval, 17) + " s)");
  }
}

// The summary's columns so far, each named once: what names it, for the message.
using Columns = std::map<std::string, std::string>;

Columns fixed_columns() {
  return {
      {"id", "the run number"}, {"status", "the run's status"}, {"message", "the run's message"}};
}

// Claims a summary column for `what`, failing at `node` if something has it already.
void claim_column(Columns& columns, const std::string& name, const std::string& what,
                  const ConfigNode& node) {
  const auto [earlier, added] = columns.emplace(summary_column(name), what);
  if (!added)
    node.fail("its summary column '" + earlier->first + "' is already " + earlier->second);
}

void read_derived_list(const ConfigNode& root, SweepSpec& spec, const UnitSystem& units,
                       Columns& columns) {
  const auto list = root.find("derived");
  if (!list) return;
  for (const auto& node : list->elements()) {
    spec.derived.push_back(read_derived(node, spec.scenarios, units));
    claim_column(columns, spec.derived.back().path, "a derived parameter's", node.at("parameter"));
  }
}

void read_metrics(const ConfigNode& root, SweepSpec& spec, Columns& columns) {
  const auto list = root.find("metrics");
  if (!list) return;
  for (const auto& node : list->elements()) {
    const SweepScenario* scenario = &spec.scenarios.front();
    if (spec.scenarios.size() > 1 || node.has("scenario")) {
      std::vector<std::string> choices;
      for (const auto& entry : spec.scenarios) choices.push_back(entry.name);
      const std::string name = node.choice("scenario", choices);
      for (const auto& entry : spec.scenarios)
        if (entry.name == name) scenario = &entry;
    }
    MetricSpec metric = read_metric(node, scenario->name, *scenario->scenario);
    if (metric.name.empty() || metric.name.find('/') != std::string::npos)
      node.at("name").fail("a metric's name must be non-empty and hold no '/'");
    claim_column(columns, metric.name, "metric '" + metric.name + "''s", node.at("name"));
    spec.metrics.push_back(std::move(metric));
  }
}

}  // namespace

std::string summary_column(const std::string& name) {
  std::string column = name;
  std::replace(column.begin(), column.end(), '/', '.');
  return column;
}

SweepSpec load_sweep(const std::string& file, const std::vector<std::string>& overrides,
                     std::shared_ptr<const UnitSystem> units) {
  const ConfigNode root = ConfigNode::load_file(file, overrides, units);
  root.declare(
      {"sweep", "scenario", "scenarios", "set", "combine", "axes", "derived", "metrics", "store"});
  SweepSpec spec;
  spec.file = file;
  const ConfigNode header = root.at("sweep");
  spec.name = header.text("name");
  spec.seed = static_cast<std::uint64_t>(header.integer_or("seed", 1, ValueCheck::non_negative()));
  spec.scenarios = read_scenarios(root, file, read_set(root), units);
  read_axes(root, spec.scenarios, units, spec);
  Columns columns = fixed_columns();
  for (const auto& axis : spec.axes) claim_column(columns, axis.path, "an axis'", root.at("axes"));
  read_derived_list(root, spec, *units, columns);
  read_metrics(root, spec, columns);
  read_store(root, spec);
  root.reject_unknown_keys();
  spec.resolved_yaml = root.resolved_yaml();
  return spec;
}

std::size_t decimation_stride(double interval, double output_interval) {
  const double ratio = interval / output_interval;
  if (!(std::round(ratio) >= 1.0) || std::abs(ratio - std::round(ratio)) > 1e-9 * ratio) return 0;
  return static_cast<std::size_t>(std::llround(ratio));
}

}  // namespace tcpmsim::sweep
