#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "analysis/control_task_runner.h"

namespace tcpmsim {

// A joint-angle task of an antagonistic pair (controller type joint_angle, self-sensing), run
// as the single-muscle tasks are (section 7.3.4): first each muscle's estimator is calibrated
// while the loop holds the angle at 0 through self-sensing (both muscles near their
// pre-deflection; the offset of each is mean(true - estimated deflection) over 10 s after
// 30 s), then the task
// runs with both offsets applied and is analysed by the same functions (step_rise_times,
// sweep_frequency_response, bandwidth_3db) on the true angle against the reference.
// estimation_errors: estimated - true angle over the task [rad] (none under encoder feedback).
struct PairTaskResult : TaskAnalysis {
  std::string scenario;
  double left_offset = 0.0;   // [m], added to the left estimator's deflection
  double right_offset = 0.0;  // [m]
  SolverStatistics statistics;
};

// Whether the scenario is a joint-angle task (it has a joint-angle controller).
bool is_pair_task(const std::string& config, const std::vector<std::string>& overrides,
                  std::shared_ptr<const UnitSystem> units);

// Loads the pair tasks and checks them (a joint-angle controller; with self-sensing, an
// estimator on each side) before anything runs: std::invalid_argument naming the problem.
std::vector<PairTaskResult> run_pair_tasks(const std::vector<std::string>& configs,
                                           const ControlTaskSettings& settings,
                                           std::shared_ptr<const UnitSystem> units);

// Each pair task under its scenario's name: calibration_offsets [left, right] (m) and its
// analysis (write_task_analysis, errors in rad).
void write_pair_tasks(Hdf5Writer& file, const std::vector<PairTaskResult>& results);

// The pair beside the single muscle: rise times of the steps that heat and of those that
// cool (for the pair, towards either side, each heated by one muscle), and the bandwidths.
std::string format_pair_comparison(const std::vector<PairTaskResult>& pair,
                                   const std::vector<ControlTaskResult>& single);

}  // namespace tcpmsim
