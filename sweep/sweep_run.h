#pragma once

#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "sim/config/units.h"
#include "sweep/sweep_spec.h"

namespace tcpmsim::sweep {

// One stored trace of one scenario of a run: time and every recorded channel ("group/name").
struct RunTrace {
  std::string scenario;
  std::vector<double> time;
  std::vector<std::string> channels;
  std::vector<std::string> units;
  std::vector<std::vector<double>> values;  // by channel
};

// What one run of a sweep gives: a row of the summary and, if the sweep stores them, traces.
struct RunResult {
  std::size_t id = 0;
  std::vector<double> values;   // the axes' values then the derived parameters', SI
  std::vector<double> metrics;  // NaN where not available
  bool succeeded = true;
  std::string message;  // why it failed, or why a metric is missing
  double wall_seconds = 0.0;
  std::vector<RunTrace> traces;
};

// Builds a scenario again for a run with structural axes. Loading reads units, which udunits2
// cannot do on two threads at once, so loads are serialised.
class ScenarioLoader {
 public:
  explicit ScenarioLoader(std::shared_ptr<const UnitSystem> units);
  std::shared_ptr<const Scenario> load(const std::string& file,
                                       const std::vector<std::string>& overrides);

 private:
  std::shared_ptr<const UnitSystem> units_;
  std::mutex mutex_;
};

// Runs every scenario of the sweep at run `id`: sets the axes' values and the derived
// parameters in a fresh context of the assembled model, integrates in memory, evaluates the
// metrics and keeps the traces the sweep stores. Never throws for the run's own failure (a
// parameter invalid at this point, a solver failure): it is reported in the result.
RunResult execute_run(const SweepSpec& spec, std::size_t id, ScenarioLoader& loader);

// The names and units of a summary's value columns: the axes, then the derived parameters.
std::vector<std::pair<std::string, std::string>> value_columns(const SweepSpec& spec);

}  // namespace tcpmsim::sweep
