#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "analysis/control_tasks.h"
#include "sim/config/units.h"
#include "sim/integrator.h"

namespace tcpmsim {

// One chapter-7 control task (section 7.3.4), run as the thesis ran it: first the calibration
// of the estimates (the testing machine holds 20 mm for the deflection offset, averaged over
// 10 s; then it holds 0.40 N while the Muscle Drive controls the deflection, for the force
// offset, averaged over 30 s), then the task with both offsets applied.
struct ControlTaskResult {
  std::string scenario;
  bool controls_deflection = false;
  double deflection_offset = 0.0;                // [m], added to the estimate
  double force_offset = 0.0;                     // [N]
  std::vector<StepRise> rises;                   // step tasks
  std::vector<FrequencyResponsePoint> response;  // sweep tasks
  std::optional<double> bandwidth;               // [Hz]
  std::vector<double> estimation_errors;         // of the controlled quantity, over the task
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

// The thesis' results (7.4) beside ours: rise-time ranges, -3 dB bandwidths and estimation
// errors (mean and 95 % band) for deflection and force control, plus the Bode points.
std::string format_control_task_report(const std::vector<ControlTaskResult>& results);
void write_control_task_report(const std::vector<ControlTaskResult>& results,
                               const std::string& path);

}  // namespace tcpmsim
