#include "analysis/pair_task_runner.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "analysis/task_runs.h"
#include "controllers/joint_angle_controller.h"
#include "kinds/standard_kinds.h"
#include "models/antagonistic_joint.h"
#include "signals/control_task_signals.h"
#include "signals/piecewise_constant_signal.h"
#include "sim/config/config_error.h"
#include "sim/parallel_runs.h"

namespace tcpmsim {

namespace {

// Section 7.3.4's deflection calibration: the loop holds the joint's middle through
// self-sensing (as the thesis calibrates force under deflection control), and each muscle's
// offset is mean(true - estimated deflection) there, wherever the biased loop settles.

// The names a pair task's analysis reads: the joint's, and each side's estimator (none when
// the controller reads the joint's encoder).
struct PairNames {
  std::string joint, controller, left_estimator, right_estimator;
  bool self_sensing() const { return !left_estimator.empty(); }
};

PairNames names_of(const Scenario& scenario) {
  const System& system = *scenario.system;
  const auto* controller = system.find<JointAngleController>();
  const auto* joint = system.find<AntagonisticJoint>();
  if (!controller || !joint)
    throw std::invalid_argument(scenario.settings.name + ": no joint-angle task");
  const auto* left = system.source_of(*controller, "left_deflection");
  const auto* right = system.source_of(*controller, "right_deflection");
  if (!left || !right) return {joint->group(), controller->group(), "", ""};
  return {joint->group(), controller->group(), left->group, right->group};
}

std::string offset_path(const std::string& estimator) {
  return estimator + ".calibration.deflection_offset";
}

// The two runs of one task, loaded up front: unit conversions take udunits2's one lock.
struct PreparedPairTask {
  Scenario calibration, task;
  PairNames names;
};

// A task is steps (rise times) or the stepped sine sweep (frequency response): a reference that
// is neither (a plain sine, a constant) has nothing to analyse.
void check_reference(const std::string& config, const Scenario& scenario, const PairNames& names) {
  const Context context = scenario.make_context();
  const Signal& reference =
      context.signal(*scenario.system->signal_slot(names.controller, "reference"));
  const bool steps = dynamic_cast<const PiecewiseConstantSignal*>(&reference) &&
                     std::isfinite(reference.next_breakpoint_after(0.0));
  if (!steps && !dynamic_cast<const SteppedSineSignal*>(&reference)) {
    throw ConfigError(SourceLocation{config, 0, 0, ""}, names.controller + ".reference",
                      "a control task's reference is a step sequence (or steps) or a "
                      "stepped_sine_sweep; this one is neither");
  }
}

PreparedPairTask prepare(const std::string& config, const ControlTaskSettings& settings,
                         const std::shared_ptr<const UnitSystem>& units) {
  PreparedPairTask prepared{{}, load_scenario(config, settings.overrides, units), {}};
  prepared.names = names_of(prepared.task);
  check_reference(config, prepared.task, prepared.names);
  if (settings.calibrate && prepared.names.self_sensing()) {
    std::vector<std::string> hold = settings.overrides;
    hold.insert(
        hold.end(),
        {prepared.names.controller + ".reference=0 rad",
         "scenario.duration=" + std::to_string(kCalibrationSettle + kCalibrationAverage) + " s"});
    prepared.calibration = load_scenario(config, hold, units);
  }
  return prepared;
}

void calibrate(PreparedPairTask& prepared, PairTaskResult& result, Context& task) {
  const PairNames& n = prepared.names;
  Context hold = prepared.calibration.make_context();
  const auto record = simulate_in_memory(prepared.calibration, hold);
  const double end = kCalibrationSettle + kCalibrationAverage;
  result.left_offset = offset_over(record, n.joint + "/left_deflection",
                                   n.left_estimator + "/deflection", kCalibrationSettle, end);
  result.right_offset = offset_over(record, n.joint + "/right_deflection",
                                    n.right_estimator + "/deflection", kCalibrationSettle, end);
  add_to(task, offset_path(n.left_estimator), result.left_offset);
  add_to(task, offset_path(n.right_estimator), result.right_offset);
}

PairTaskResult run_task(PreparedPairTask& prepared, bool calibrated) {
  PairTaskResult result;
  result.scenario = prepared.task.settings.name;
  const PairNames& n = prepared.names;
  Context task = prepared.task.make_context();
  if (calibrated && n.self_sensing()) calibrate(prepared, result, task);
  const auto record = simulate_in_memory(prepared.task, task, &result.statistics);
  // The task starts at the reference's first change; before it the joint settles. Under
  // self-sensing the controller's angle is the estimate; under the encoder, a reading.
  const Signal& reference =
      task.signal(*prepared.task.system->signal_slot(n.controller, "reference"));
  analyse_task(record, reference, n.controller + "/reference", n.joint + "/angle",
               n.self_sensing() ? n.controller + "/angle" : "", result);
  return result;
}

// Median of the reached rise times and the count charged their hold.
std::string rises_text(const std::vector<StepRise>& rises, bool (*selected)(const StepRise&)) {
  std::vector<double> reached;
  int outliers = 0;
  for (const auto& rise : rises) {
    if (!selected(rise)) continue;
    if (rise.reached)
      reached.push_back(rise.rise_time);
    else
      ++outliers;
  }
  char text[128];
  if (reached.empty()) {
    std::snprintf(text, sizeof text, "none reached (%d at the hold)", outliers);
  } else {
    std::sort(reached.begin(), reached.end());
    std::snprintf(text, sizeof text, "median %.1f s, %.1f-%.1f s, %d at the hold",
                  reached[reached.size() / 2], reached.front(), reached.back(), outliers);
  }
  return text;
}

bool rising(const StepRise& rise) {
  return rise.target > rise.start;
}
bool falling(const StepRise& rise) {
  return rise.target < rise.start;
}
bool any_step(const StepRise&) {
  return true;
}

std::string bandwidth_text(const std::optional<double>& bandwidth, bool swept) {
  if (!swept) return "no sweep given";
  if (!bandwidth) return "not bracketed by the sweep";
  char text[32];
  std::snprintf(text, sizeof text, "%.3f Hz", *bandwidth);
  return text;
}

}  // namespace

bool is_pair_task(const std::string& config, const std::vector<std::string>& overrides,
                  std::shared_ptr<const UnitSystem> units) {
  const Scenario scenario = load_scenario(config, overrides, std::move(units));
  return scenario.system->find<JointAngleController>() != nullptr;
}

std::vector<PairTaskResult> run_pair_tasks(const std::vector<std::string>& configs,
                                           const ControlTaskSettings& settings,
                                           std::shared_ptr<const UnitSystem> units) {
  std::vector<PreparedPairTask> prepared;
  for (const auto& config : configs) prepared.push_back(prepare(config, settings, units));
  std::vector<PairTaskResult> results(configs.size());
  run_in_parallel(configs, settings.threads,
                  [&](std::size_t k) { results[k] = run_task(prepared[k], settings.calibrate); });
  return results;
}

void write_pair_tasks(Hdf5Writer& file, const std::vector<PairTaskResult>& results) {
  for (const auto& result : results) {
    file.write(result.scenario + "/calibration_offsets",
               std::vector<double>{result.left_offset, result.right_offset}, "m");
    write_task_analysis(file, result.scenario, result, "rad");
  }
}

std::string format_pair_comparison(const std::vector<PairTaskResult>& pair,
                                   const std::vector<ControlTaskResult>& single) {
  std::vector<StepRise> pair_rises, single_rises;
  std::optional<double> pair_bandwidth, single_bandwidth;
  bool pair_swept = false, single_swept = false;
  for (const auto& result : pair) {
    pair_rises.insert(pair_rises.end(), result.rises.begin(), result.rises.end());
    if (!result.response.empty()) pair_swept = true, pair_bandwidth = result.bandwidth;
  }
  for (const auto& result : single) {
    if (!result.controls_deflection) continue;
    single_rises.insert(single_rises.end(), result.rises.begin(), result.rises.end());
    if (!result.response.empty()) single_swept = true, single_bandwidth = result.bandwidth;
  }
  std::string text = "\nAntagonistic pair (joint angle) beside the single muscle (deflection):\n";
  char line[320];
  const auto row = [&](const char* what, const std::string& pair_text,
                       const std::string& single_text) {
    std::snprintf(line, sizeof line, "  %-22s pair %-44s single %s\n", what, pair_text.c_str(),
                  single_text.c_str());
    text += line;
  };
  // A single muscle under a constant force contracts when heated: its steps down in deflection
  // heat, its steps up wait for cooling. Each of the pair's directions heats one muscle.
  row("rise times, heated", rises_text(pair_rises, rising) + " (angle up)",
      rises_text(single_rises, falling) + " (deflection down)");
  row("rise times, other way", rises_text(pair_rises, falling) + " (angle down)",
      rises_text(single_rises, rising) + " (deflection up: cooling)");
  row("rise times, all steps", rises_text(pair_rises, any_step),
      rises_text(single_rises, any_step));
  row("-3 dB bandwidth", bandwidth_text(pair_bandwidth, pair_swept),
      bandwidth_text(single_bandwidth, single_swept));
  for (const auto& result : pair) {
    if (result.estimation_errors.empty()) {
      text += "  " + result.scenario + ": encoder feedback, nothing to calibrate\n";
      continue;
    }
    std::vector<double> errors;
    for (double e : result.estimation_errors)
      if (std::isfinite(e)) errors.push_back(e);
    const ErrorStatistics statistics = error_statistics(errors);
    std::snprintf(line, sizeof line,
                  "  %s: calibration offsets %+.3f mm (left), %+.3f mm (right); angle error "
                  "%+.4f +- %.4f rad (mean, 95 %% band)\n",
                  result.scenario.c_str(), 1e3 * result.left_offset, 1e3 * result.right_offset,
                  statistics.mean, statistics.half_width_95);
    text += line;
  }
  return text;
}

}  // namespace tcpmsim
