#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "sim/config/units.h"
#include "sim/scenario.h"
#include "sweep/metrics.h"

namespace tcpmsim::sweep {

// A sweep file read and checked: its scenarios loaded once, every run's values generated, every
// metric's channels found. Whatever is wrong with the file is reported here, located, before
// any run starts.

// A scenario the sweep runs at every point, under its name in the file ("step", "loop"; a
// single `scenario:` is named "scenario").
struct SweepScenario {
  std::string name;
  std::string file;
  std::vector<std::string> overrides;  // the sweep's `set:`, applied to every scenario
  std::shared_ptr<const Scenario> scenario;
};

// One varied quantity. A model parameter is set in each run's context (`unit` its SI unit);
// any other scenario key (scenario.seed, solver.rtol, a kind) is a structural axis: its values
// are applied as --set texts and the scenario is built again for the run.
struct Axis {
  std::string path;
  std::string unit;                // SI; "" for a structural axis
  bool structural = false;         // see above
  std::vector<std::string> texts;  // a structural axis' values as --set texts, by run
};

// A parameter set from others at every run: value = factor * prod(multiply) / prod(divide)
// (an estimator's model kept matched to the plant: kappa_c = hA / C).
struct DerivedParameter {
  std::string path;
  std::string unit;  // SI
  std::vector<std::string> multiply;
  std::vector<std::string> divide;
  double factor = 1.0;
};

enum class TraceStorage { none, decimated, full };

struct SweepSpec {
  std::string name;
  std::string file;
  std::string resolved_yaml;  // the sweep file as read, with defaults: the sweep's identity
  std::uint64_t seed = 0;
  std::vector<SweepScenario> scenarios;
  std::vector<Axis> axes;
  std::vector<std::vector<double>> runs;  // runs[id][axis]; NaN for a structural axis' text
  std::vector<DerivedParameter> derived;
  std::vector<MetricSpec> metrics;
  TraceStorage traces = TraceStorage::none;
  double trace_interval = 0.0;  // [s], decimated traces
};

// The summary's dataset name of a parameter path or metric: '/' (a member's parameter,
// "bundle/m03.mechanics.k1") becomes '.', so the summary stays flat.
std::string summary_column(const std::string& name);

// Reads `file` (overrides: --set on the sweep file itself). Scenario files are found relative
// to the sweep file. Throws ConfigError located at the offending key.
// A file's `set:` list: "path=value" overrides for the scenarios it names (a sweep's, a fit's).
std::vector<std::string> read_set(const ConfigNode& root);
// A scenario that fails to load under `set:` is reported at the setting that made it fail (the
// error names that --set), or at `set:` as a whole when the scenario file has no line to blame;
// an error of the scenario file itself stands as it is (returns).
void blame_set(const ConfigNode& root, const std::string& scenario, const ConfigError& error);

SweepSpec load_sweep(const std::string& file, const std::vector<std::string>& overrides,
                     std::shared_ptr<const UnitSystem> units);

// Every how many samples a trace kept every `interval` keeps one of a record made every
// `output_interval`; 0 when `interval` is no whole multiple of it.
std::size_t decimation_stride(double interval, double output_interval);

}  // namespace tcpmsim::sweep
