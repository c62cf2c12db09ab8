#include "sweep/sweep_run.h"

#include <chrono>
#include <cmath>
#include <stdexcept>

#include "kinds/standard_kinds.h"
#include "sim/memory_record.h"
#include "sim/not_a_number.h"
#include "sim/run.h"
#include "sim/value_check.h"

namespace tcpmsim::sweep {
namespace {

bool has_parameter(const Scenario& scenario, const std::string& path) {
  return scenario.system->parameter_index(path).has_value();
}

// value = factor * prod(multiply) / prod(divide), from the context's values.
double derived_value(const DerivedParameter& derived, const Context& context) {
  double value = derived.factor;
  for (const auto& path : derived.multiply) value *= context.parameter(path);
  for (const auto& path : derived.divide) value /= context.parameter(path);
  return value;
}

// Every how many samples a run's trace keeps one. The sweep file checked its scenarios' output
// intervals; a structural axis may change one, so a run checks its own before it integrates.
std::size_t trace_stride(const SweepSpec& spec, const Scenario& scenario) {
  if (spec.traces != TraceStorage::decimated) return 1;
  const std::size_t stride =
      decimation_stride(spec.trace_interval, scenario.settings.output_interval);
  if (stride == 0)
    throw std::runtime_error("store.interval (" + number_text(spec.trace_interval) +
                             " s) is no multiple of this run's output interval (" +
                             number_text(scenario.settings.output_interval, 17) +
                             " s): its traces cannot be decimated");
  return stride;
}

RunTrace keep_trace(const SweepScenario& entry, const Scenario& scenario,
                    const MemoryRecord& record, std::size_t stride) {
  RunTrace trace;
  trace.scenario = entry.name;
  for (std::size_t k = 0; k < record.time.size(); k += stride) trace.time.push_back(record.time[k]);
  for (const auto& channel : scenario.system->channels()) {
    if (!channel.recorded) continue;
    const auto& all = record[channel.group + "/" + channel.name];
    std::vector<double> kept;
    for (std::size_t k = 0; k < all.size(); k += stride) kept.push_back(all[k]);
    trace.channels.push_back(channel.group + "/" + channel.name);
    trace.units.push_back(channel.unit);
    trace.values.push_back(std::move(kept));
  }
  return trace;
}

void note(RunResult& result, const std::string& text) {
  result.message += (result.message.empty() ? "" : "; ") + text;
}

// One scenario of the run; throws on the run's failure.
void run_scenario_at(const SweepSpec& spec, const SweepScenario& entry, std::size_t id,
                     ScenarioLoader& loader, RunResult& result) {
  std::shared_ptr<const Scenario> scenario = entry.scenario;
  std::vector<std::string> structural;
  for (std::size_t a = 0; a < spec.axes.size(); ++a) {
    if (spec.axes[a].structural)
      structural.push_back(spec.axes[a].path + "=" + spec.axes[a].texts[id]);
  }
  if (!structural.empty()) {
    auto overrides = entry.overrides;
    overrides.insert(overrides.end(), structural.begin(), structural.end());
    scenario = loader.load(entry.file, overrides);
  }
  Context context = scenario->make_context();
  for (std::size_t a = 0; a < spec.axes.size(); ++a) {
    const Axis& axis = spec.axes[a];
    if (!axis.structural && has_parameter(*scenario, axis.path))
      context.set_parameter(axis.path, spec.runs[id][a]);
  }
  for (std::size_t d = 0; d < spec.derived.size(); ++d) {
    const DerivedParameter& derived = spec.derived[d];
    if (!has_parameter(*scenario, derived.path)) continue;
    const double value = derived_value(derived, context);
    context.set_parameter(derived.path, value);
    result.values[spec.axes.size() + d] = value;
  }
  const std::size_t stride = trace_stride(spec, *scenario);
  MemoryRecord record(*scenario->system);
  integrate(*scenario, context, record);
  for (std::size_t m = 0; m < spec.metrics.size(); ++m) {
    if (spec.metrics[m].scenario != entry.name) continue;
    // A metric the record cannot give (too short a window for a fit) is missing from this
    // run's row; the run itself stands.
    try {
      const MetricValue value = evaluate_metric(spec.metrics[m], record, context);
      result.metrics[m] = value.value;
      if (!value.note.empty()) note(result, spec.metrics[m].name + ": " + value.note);
    } catch (const std::exception& error) {
      note(result, spec.metrics[m].name + ": " + error.what());
    }
  }
  if (spec.traces != TraceStorage::none)
    result.traces.push_back(keep_trace(entry, *scenario, record, stride));
}

}  // namespace

ScenarioLoader::ScenarioLoader(std::shared_ptr<const UnitSystem> units)
    : units_(std::move(units)) {}

std::shared_ptr<const Scenario> ScenarioLoader::load(const std::string& file,
                                                     const std::vector<std::string>& overrides) {
  const std::lock_guard lock(mutex_);
  return std::make_shared<const Scenario>(load_scenario(file, overrides, units_));
}

RunResult execute_run(const SweepSpec& spec, std::size_t id, ScenarioLoader& loader) {
  const auto started = std::chrono::steady_clock::now();
  RunResult result;
  result.id = id;
  result.values = spec.runs[id];
  result.values.resize(spec.axes.size() + spec.derived.size(), kNaN);
  result.metrics.assign(spec.metrics.size(), kNaN);
  for (const auto& entry : spec.scenarios) {
    try {
      run_scenario_at(spec, entry, id, loader, result);
    } catch (const std::exception& error) {
      result.succeeded = false;
      note(result,
           (spec.scenarios.size() > 1 ? "scenario '" + entry.name + "': " : "") + error.what());
    }
  }
  result.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return result;
}

std::vector<std::pair<std::string, std::string>> value_columns(const SweepSpec& spec) {
  std::vector<std::pair<std::string, std::string>> columns;
  for (const auto& axis : spec.axes)
    columns.emplace_back(axis.path, axis.structural ? "" : axis.unit);
  for (const auto& derived : spec.derived) columns.emplace_back(derived.path, derived.unit);
  return columns;
}

}  // namespace tcpmsim::sweep
