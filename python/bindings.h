#pragma once

// The Python module tcpmsim._core: a thin layer over the C++ API (kinds/standard_kinds.h,
// sim/memory_run.h, sweep/run_pool.h). It holds no physics and reads no file itself.

#include <pybind11/pybind11.h>

#include <memory>
#include <string>
#include <vector>

#include "sim/config/units.h"
#include "sim/memory_run.h"
#include "sim/scenario.h"

namespace tcpmsim::python {

// A scenario as Python holds it: where it came from and the overrides set on it, and the
// scenario they build (rebuilt after every set, so that a bad value raises at once).
class PyScenario {
 public:
  // `overrides` ("path=value") apply from the start, as the command line's --set: for a
  // scenario that cannot be built without them (a measurement file to replay).
  static PyScenario from_file(const std::string& path, std::vector<std::string> overrides = {});
  static PyScenario from_text(const std::string& text, std::vector<std::string> overrides = {});

  // Applies "path=value" as the command line's --set does; on error the scenario is unchanged.
  void set(const std::string& path, const std::string& value);
  // The scenario with extra overrides (a run's duration and output rate), built afresh.
  std::shared_ptr<const Scenario> with(const std::vector<std::string>& extra) const;
  const Scenario& scenario() const { return *scenario_; }
  std::shared_ptr<const Scenario> shared() const { return scenario_; }
  const std::vector<std::string>& overrides() const { return overrides_; }
  const std::string& source() const { return source_; }
  bool is_text() const { return is_text_; }

 private:
  PyScenario(std::string source, bool is_text, std::vector<std::string> overrides);
  std::shared_ptr<const Scenario> load(const std::vector<std::string>& overrides) const;

  std::string source_;  // a path, or the YAML text itself
  bool is_text_ = false;
  std::vector<std::string> overrides_;
  std::shared_ptr<const UnitSystem> units_;
  std::shared_ptr<const Scenario> scenario_;
};

// A finished run: its samples (shared with the numpy arrays handed out) and the scenario that
// made it (for the resolved config and for save).
struct PyResult {
  std::shared_ptr<const MemoryRun> run;
  std::shared_ptr<const Scenario> scenario;
};

// Integrates with the GIL released; Ctrl-C interrupts the run (KeyboardInterrupt). A run whose
// samples would exceed `limit_bytes` raises ConfigError before it starts, as `tcpmsim run`.
PyResult run_scenario(const std::shared_ptr<const Scenario>& scenario,
                      double limit_bytes = kDefaultRecordLimit);
// Runs on `jobs` threads (the sweeps' run pool), the GIL released; a solver failure is that
// result's status, not an exception.
std::vector<PyResult> run_scenarios(const std::vector<std::shared_ptr<const Scenario>>& scenarios,
                                    int jobs);

// `value` as a number (a float, an int, anything with __float__: numpy's); else a TypeError
// "<what>: expected <expected>, got <repr>" (pybind11's own cast error is a bare RuntimeError).
double number_argument(const pybind11::handle& value, const std::string& what,
                       const std::string& expected = "a number");

void bind_errors(pybind11::module_& module);
void bind_scenario(pybind11::module_& module);
void bind_result(pybind11::module_& module);
void bind_analysis(pybind11::module_& module);
void bind_control_task(pybind11::module_& module);
void bind_simulator(pybind11::module_& module);

}  // namespace tcpmsim::python
