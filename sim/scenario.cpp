#include "sim/scenario.h"

#include <algorithm>

#include "sim/kind_listing.h"

namespace tcpmsim {

namespace {

// output.compression: none (the default; not written into the resolved scenario, so records
// made before the key existed keep their bits) or deflate, at compression_level 1-9 (default 1).
int read_compression(const ConfigNode& output) {
  if (!output.has("compression")) {
    if (output.has("compression_level"))
      output.at("compression_level").fail("give it with 'compression: deflate'");
    return 0;
  }
  if (output.choice("compression", {"none", "deflate"}) == "none") {
    if (output.has("compression_level"))
      output.at("compression_level").fail("'compression: none' takes no level");
    return 0;
  }
  return static_cast<int>(output.integer_or("compression_level", 1, ValueCheck::between(1, 9)));
}

ScenarioSettings read_settings(const ConfigNode& root, const KindRegistry& kinds) {
  ScenarioSettings settings;
  root.declare({"scenario", "output", "solver", "measurement"});
  for (const Category& category : kinds.categories()) {
    if (!category.top_level()) continue;
    root.declare({category.name, category.plural});
  }
  const ConfigNode scenario = root.at("scenario");
  scenario.declare({"name", "description", "duration", "seed"});
  settings.name = scenario.text("name");
  if (settings.name.empty() || settings.name.find_first_of("/\\ ") != std::string::npos) {
    scenario.at("name").fail(
        "expected a non-empty name without spaces or slashes (it names the output file)");
  }
  if (scenario.has("description")) settings.description = scenario.text("description");
  settings.duration = scenario.quantity("duration", "s", ValueCheck::positive());
  settings.seed =
      static_cast<std::uint64_t>(scenario.integer_or("seed", 0, ValueCheck::non_negative()));
  const ConfigNode output = root.at("output");
  output.declare({"rate", "start", "compression", "compression_level"});
  const double rate = output.quantity("rate", "Hz", ValueCheck::positive());
  settings.output_interval = 1.0 / rate;
  settings.output_rate_location = output.at("rate").location();
  settings.output_start = output.quantity_or("start", "s", 0.0, ValueCheck::non_negative());
  if (settings.output_start >= settings.duration) {
    output.at("start").fail("expected a start before the end of the scenario (" +
                            std::to_string(settings.duration) + " s)");
  }
  settings.compression_level = read_compression(output);
  if (const auto measurement = root.find("measurement")) {
    measurement->declare({"file"});
    settings.measurement_file = file_named_by(measurement->at("file"));
  }
  return settings;
}

void read_absolute_tolerances(const ConfigNode& solver, const System& system,
                              SolverSettings& settings) {
  settings.absolute_tolerances.clear();
  const auto overrides = solver.find("atol");
  for (const auto& state : system.states()) {
    double tolerance = state.absolute_tolerance;
    const auto dot = state.name.rfind('.');
    const std::string group = state.name.substr(0, dot), name = state.name.substr(dot + 1);
    if (overrides) {
      if (auto group_node = overrides->find(group)) {
        if (auto value = group_node->find(name))
          tolerance = value->as_quantity(state.unit, ValueCheck::positive());
      }
    }
    settings.absolute_tolerances.push_back(tolerance);
  }
}

// Warm restarts are the default with KLU, the solver for large systems, where a restart's fresh
// Jacobian and step estimate dominate. Dense and band stay cold unless asked: their records
// were validated that way, and a default not written into the resolved config keeps them.
std::string read_restart(const ConfigNode& solver, LinearSolverKind linear_solver) {
  const std::vector<std::string> options{"cold", "warm"};
  if (linear_solver == LinearSolverKind::klu || linear_solver == LinearSolverKind::gmres)
    return solver.choice_or("restart", options, "warm");
  if (const auto given = solver.find("restart")) return given->as_choice(options);
  return "cold";
}

// The default linear solver: KLU (with warm restarts) for a BDF system of this many states or
// more, dense below. bench/bench_bundle_scaling.py: dense and KLU cost the same at 14 states
// (7 muscles), KLU is 2.4 times faster at 20 and 27 times at 200.
constexpr int kSparseFromStates = 20;

LinearSolverKind default_linear_solver(const System& system, IntegrationMethod method) {
  return method == IntegrationMethod::bdf && system.state_size() >= kSparseFromStates
             ? LinearSolverKind::klu
             : LinearSolverKind::dense;
}

SolverSettings read_solver(const ConfigNode& root, const System& system) {
  SolverSettings settings;
  const auto solver = root.find("solver");
  if (!solver) {
    for (const auto& state : system.states())
      settings.absolute_tolerances.push_back(state.absolute_tolerance);
    settings.linear_solver = default_linear_solver(system, settings.method);
    if (settings.linear_solver == LinearSolverKind::klu) settings.restart = RestartKind::warm;
    return settings;
  }
  solver->declare({"method", "rtol", "atol", "linear_solver", "restart", "max_step", "initial_step",
                   "max_steps", "sensitivity_error_control"});
  settings.method = solver->choice_or("method", {"bdf", "adams"}, "bdf") == "adams"
                        ? IntegrationMethod::adams
                        : IntegrationMethod::bdf;
  settings.relative_tolerance =
      solver->number_or("rtol", settings.relative_tolerance, ValueCheck::between(1e-14, 0.1));
  const auto& names = linear_solver_names();
  const std::string kind = solver->choice_or(
      "linear_solver", names, linear_solver_name(default_linear_solver(system, settings.method)));
  settings.linear_solver =
      static_cast<LinearSolverKind>(std::find(names.begin(), names.end(), kind) - names.begin());
  settings.restart = read_restart(*solver, settings.linear_solver) == "warm" ? RestartKind::warm
                                                                             : RestartKind::cold;
  settings.max_step = solver->quantity_or("max_step", "s", 0.0, ValueCheck::non_negative());
  settings.initial_step = solver->quantity_or("initial_step", "s", 0.0, ValueCheck::non_negative());
  settings.max_steps = solver->integer_or("max_steps", settings.max_steps, ValueCheck::at_least(1));
  settings.sensitivity_error_control =
      solver->boolean_or("sensitivity_error_control", settings.sensitivity_error_control);
  read_absolute_tolerances(*solver, system, settings);
  return settings;
}

// The parameter an assignment sets, if it sets one of `system` by a single value: its index.
std::optional<int> parameter_of(const Assignment& assignment, const System& system,
                                const ConfigNode& document) {
  if (!assignment.value.IsScalar()) return std::nullopt;
  // The parameter path of a scenario path: as the document names its instances.
  const auto index = system.parameter_index(document.parameter_path_of(assignment.path));
  if (!index || !system.parameters()[static_cast<std::size_t>(*index)].derived_from.empty())
    return std::nullopt;
  return index;
}

}  // namespace

std::vector<std::string> instance_sections(const KindRegistry& kinds) {
  std::vector<std::string> sections;
  for (const Category& category : kinds.categories())
    if (category.top_level()) sections.push_back(category.plural);
  return sections;
}

namespace {

// At the section whose builder caused it (the first origin), naming the sections of the others
// ("; from drives.a, drives.b"); at the top when none is known.
[[noreturn]] void report_assembly_error(const ConfigNode& root,
                                        const std::vector<InstanceDeclaration>& instances,
                                        const AssemblyError& error) {
  std::string message = std::string("the scenario does not assemble: ") + error.what();
  const auto& origins = error.origins();
  auto known = [&](int origin) {
    return origin >= 0 && static_cast<std::size_t>(origin) < instances.size();
  };
  std::vector<std::string> sections;
  for (std::size_t k = 1; k < origins.size(); ++k)
    if (known(origins[k])) {
      const std::string& path = instances[static_cast<std::size_t>(origins[k])].node.path();
      if (std::find(sections.begin(), sections.end(), path) == sections.end())
        sections.push_back(path);
    }
  if (sections.size() > 1) {
    message += "; from ";
    for (std::size_t k = 0; k < sections.size(); ++k) message += (k ? ", " : "") + sections[k];
  }
  if (!origins.empty() && known(origins.front()))
    instances[static_cast<std::size_t>(origins.front())].node.fail(message);
  root.fail(message);
}

}  // namespace

Scenario build_scenario(const ConfigNode& root, const KindRegistry& kinds) {
  Scenario scenario;
  scenario.settings = read_settings(root, kinds);
  ScenarioBuilder build(kinds, root, scenario.settings);
  if (build.instances().empty()) {
    std::string sections;
    for (const Category& category : kinds.categories())
      if (category.top_level())
        sections += (sections.empty() ? "" : ", ") + category.name + "/" + category.plural;
    root.fail("expected at least one instance: a section of " + sections);
  }
  // Each instance's additions and connections carry its index, so that an assembly error is
  // reported at the section that caused it.
  for (std::size_t k = 0; k < build.instances().size(); ++k) {
    const auto& instance = build.instances()[k];
    build.system().set_origin(static_cast<int>(k));
    kinds.builder<InstanceBuilder> (*instance.kind)(instance.node, instance.name, build);
  }
  build.system().set_origin(-1);
  build.run_checks();
  try {
    scenario.system = build.system().build();
  } catch (const AssemblyError& error) {
    report_assembly_error(root, build.instances(), error);
  } catch (const std::logic_error& error) {
    root.fail(std::string("the scenario does not assemble: ") + error.what());
  }
  scenario.solver = read_solver(root, *scenario.system);
  root.reject_unknown_keys(variant_keys(kinds, root.shared_units()));
  scenario.resolved_yaml = root.resolved_yaml();
  scenario.warnings = root.warnings();
  return scenario;
}

Scenario load_scenario_text(const std::string& text, const std::string& name,
                            const std::vector<std::string>& overrides,
                            std::shared_ptr<const UnitSystem> units, const KindRegistry& kinds,
                            const std::string& override_origin) {
  if (overrides.empty()) {
    Scenario scenario = build_scenario(ConfigNode::load_text(text, name, {}, units), kinds);
    scenario.source = name;
    return scenario;
  }
  const std::vector<std::string> sections = instance_sections(kinds);
  // Every override through the document: it checks them all and gives the resolved scenario.
  const ConfigNode everything =
      ConfigNode::load_text(text, name, overrides, units, sections, override_origin);
  const Scenario complete = build_scenario(everything, kinds);
  const std::vector<Assignment>& assignments = everything.assignments();
  // Those that set a parameter go to the run context instead, as long as the model built
  // without them still has that parameter.
  std::vector<std::optional<int>> complete_index(assignments.size());
  std::vector<bool> to_context(assignments.size());
  for (std::size_t k = 0; k < assignments.size(); ++k) {
    complete_index[k] = parameter_of(assignments[k], *complete.system, everything);
    to_context[k] = complete_index[k].has_value();
  }
  if (std::find(to_context.begin(), to_context.end(), true) == to_context.end()) {
    Scenario scenario = complete;
    scenario.source = name;
    return scenario;
  }
  while (true) {
    std::vector<std::string> structural;
    for (std::size_t k = 0; k < assignments.size(); ++k) {
      if (!to_context[k]) structural.push_back(overrides[k]);
    }
    const ConfigNode document =
        ConfigNode::load_text(text, name, structural, units, sections, override_origin);
    Scenario scenario = build_scenario(document, kinds);
    bool consistent = true;
    for (std::size_t k = 0; k < assignments.size(); ++k) {
      if (!to_context[k]) continue;
      const auto index = parameter_of(assignments[k], *scenario.system, document);
      if (!index) {
        to_context[k] = false;
        consistent = false;
        continue;
      }
      scenario.parameter_settings.emplace_back(
          scenario.system->parameters()[static_cast<std::size_t>(*index)].declaration.path,
          complete.system->parameters()[static_cast<std::size_t>(*complete_index[k])]
              .declaration.value);
    }
    if (!consistent) continue;
    scenario.resolved_yaml = complete.resolved_yaml;
    scenario.warnings = complete.warnings;  // the --set values' too
    scenario.source = name;
    // A value the model as built cannot take in a run (one that changes its structure, such
    // as damping where the spring was built undamped) is built into the model instead.
    try {
      Context context = scenario.make_context();
      scenario.system->prepare(context);
    } catch (const ParameterError&) {
      Scenario built = complete;
      built.source = name;
      return built;
    }
    return scenario;
  }
}

Scenario load_scenario(const std::string& file, const std::vector<std::string>& overrides,
                       std::shared_ptr<const UnitSystem> units, const KindRegistry& kinds,
                       const std::string& override_origin) {
  return load_scenario_text(read_text_file(file), file, overrides, std::move(units), kinds,
                            override_origin);
}

Context Scenario::make_context() const {
  Context context(*system);
  for (const auto& [path, value] : parameter_settings) context.set_parameter(path, value);
  return context;
}

}  // namespace tcpmsim
