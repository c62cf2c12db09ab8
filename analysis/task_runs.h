#pragma once

#include <span>
#include <string>

#include "analysis/control_task_runner.h"
#include "sim/context.h"
#include "sim/integrator.h"
#include "sim/memory_record.h"
#include "sim/scenario.h"
#include "sim/signal.h"

namespace tcpmsim {

// What the control-task runners (single muscle and pair) share: a run kept in memory, the
// calibration of section 7.3.4 read from it, and the analysis of the task.

// Section 7.3.4: the estimate is averaged over kCalibrationAverage after kCalibrationSettle.
inline constexpr double kCalibrationSettle = 30.0;   // [s]
inline constexpr double kCalibrationAverage = 10.0;  // [s], the deflection's

// Integrates `scenario` in `context`, keeping every recorded output.
MemoryRecord simulate_in_memory(const Scenario& scenario, Context& context,
                                SolverStatistics* statistics = nullptr);

// The calibration offset (7.3.4), mean(truth - estimate), over the samples with from <= t < to
// whose estimate is known.
double offset_over(const MemoryRecord& record, const std::string& truth,
                   const std::string& estimate, double from, double to);

// Adds `offset` to the parameter at `path`: measured offsets add to those the scenario
// configures (calibration_offset).
void add_to(Context& context, const std::string& path, double offset);

// The task from the reference's first change on (one sample before it, so that a first step is
// seen as one): rise times of a step task or the frequency response and bandwidth of a stepped
// sine sweep, of the channel `truth` against `reference_channel`; and the estimation errors
// `estimate` - `truth` (none when `estimate` is empty).
void analyse_task(const MemoryRecord& record, const Signal& reference,
                  const std::string& reference_channel, const std::string& truth,
                  const std::string& estimate, TaskAnalysis& analysis);
// The same on sampled series (t, r as the controller used it, the truth y and the estimate y^,
// empty for none), as a run closed outside tcpmsim (tcpmsim.control_task) records them.
void analyse_task(std::span<const double> time, std::span<const double> reference_samples,
                  std::span<const double> truth, std::span<const double> estimate,
                  const Signal& reference, TaskAnalysis& analysis);

}  // namespace tcpmsim
