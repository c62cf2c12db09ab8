#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "analysis/control_tasks.h"
#include "sim/config/units.h"
#include "sim/integrator.h"
#include "sim/io/hdf5_writer.h"

namespace tcpmsim {

// One chapter-7 control task (section 7.3.4), run as the thesis ran it: first the calibration
// of the estimates (the testing machine holds 20 mm for the deflection offset, averaged over
// 10 s; then it holds 0.40 N while the Muscle Drive controls the deflection, for the force
// offset, averaged over 30 s), then the task with both offsets applied.
// What the control-task analysis finds in one task (single muscle or pair).
struct TaskAnalysis {
  std::vector<StepRise> rises;  // step tasks
  // Per step: the largest excursion beyond the new reference, away from the old, over the
  // step's hold, as a fraction of the reference's change (overshoot_fraction); NaN for a step
  // at the first sample.
  std::vector<double> overshoots;
  std::vector<FrequencyResponsePoint> response;  // sweep tasks
  std::optional<double> bandwidth;               // [Hz]
  std::vector<double> estimation_errors;         // of the controlled quantity, over the task
  std::vector<double> tracking_errors;           // truth - reference, over the task
};

struct ControlTaskResult : TaskAnalysis {
  std::string scenario;
  bool controls_deflection = false;
  double deflection_offset = 0.0;  // [m], added to the estimate
  double force_offset = 0.0;       // [N]
  SolverStatistics statistics;
  double wall_seconds = 0.0;
};

struct ControlTaskSettings {
  std::vector<std::string> overrides;  // applied to every run (e.g. drive.fidelity=switched)
  bool calibrate = true;
  int threads = 2;
};

std::vector<ControlTaskResult> run_control_tasks(const std::vector<std::string>& configs,
                                                 const ControlTaskSettings& settings,
                                                 std::shared_ptr<const UnitSystem> units);

// Section 7.4's published results for one task kind, in SI units, as data: the report prints
// them beside ours and the record keeps them (group thesis_7_4) for offline comparison.
struct PublishedControlResults {
  double rise_time_min = 0.0;     // [s] 10-90 %, over the steps reached (the rest hit 20 s)
  double rise_time_max = 0.0;     // [s]
  double bandwidth = 0.0;         // [Hz], -3 dB of the stepped-sine sweep
  double error_mean = 0.0;        // [m] or [N], estimate minus truth over the task
  double error_half_width = 0.0;  // [m] or [N], the 95 % band around the mean
};
// Deflection control: 4.2-14.1 s, 0.039 Hz, -0.27 +- 2.14 mm; force control: 2.1-5.1 s,
// 0.056 Hz, +7.5 +- 29.0 mN.
PublishedControlResults thesis_control_results(bool deflection);

// The thesis' results (7.4) beside ours: rise-time ranges, -3 dB bandwidths and estimation
// errors (mean and 95 % band) for deflection and force control, plus the Bode points.
std::string format_control_task_report(const std::vector<ControlTaskResult>& results);
// Writes one group per task (its calibration offsets and write_task_analysis); `more` may add
// groups (the pair tasks) before the file is committed.
void write_control_task_report(const std::vector<ControlTaskResult>& results,
                               const std::string& path, const Provenance& provenance,
                               const std::function<void(Hdf5Writer&)>& more = {});
// A task's analysis under `group`: step_time, rise_time, reached; or frequency, magnitude,
// phase, bandwidth; and estimation_error (in error_unit).
void write_task_analysis(Hdf5Writer& file, const std::string& group, const TaskAnalysis& analysis,
                         const char* error_unit);

}  // namespace tcpmsim
