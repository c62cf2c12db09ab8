// tcpmsim.control_task: the analysis `tcpmsim control-tasks` makes of a chapter-7 task, on a run
// closed by any controller (the built-in PID, or one outside tcpmsim through tcpmsim.Simulator).
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <span>
#include <string>
#include <vector>

#include "analysis/control_tasks.h"
#include "analysis/record_channels.h"
#include "analysis/task_runs.h"
#include "python/bindings.h"
#include "sim/config/config_error.h"

namespace py = pybind11;

namespace tcpmsim::python {
namespace {

py::array_t<double> array_of(const std::vector<double>& values) {
  return py::array_t<double>(static_cast<py::ssize_t>(values.size()), values.data());
}

py::dict statistics_dict(const std::vector<double>& errors) {
  const ErrorStatistics statistics = error_statistics(errors);
  py::dict result;
  result["count"] = statistics.count;
  result["mean"] = statistics.mean;
  result["standard_deviation"] = statistics.standard_deviation;
  result["half_width_95"] = statistics.half_width_95;
  result["rmse"] = statistics.rmse;
  return result;
}

py::dict rises_dict(const TaskAnalysis& analysis) {
  std::vector<double> step_time, target, start, rise_time;
  std::vector<bool> reached;
  for (const auto& rise : analysis.rises) {
    step_time.push_back(rise.step_time);
    target.push_back(rise.target);
    start.push_back(rise.start);
    rise_time.push_back(rise.rise_time);
    reached.push_back(rise.reached);
  }
  py::dict result;
  result["step_time"] = array_of(step_time);
  result["target"] = array_of(target);
  result["start"] = array_of(start);
  result["rise_time"] = array_of(rise_time);
  result["reached"] = reached;
  result["overshoot"] = array_of(analysis.overshoots);
  return result;
}

py::dict response_dict(const TaskAnalysis& analysis) {
  std::vector<double> frequency, magnitude, magnitude_db, phase;
  for (const auto& point : analysis.response) {
    frequency.push_back(point.frequency);
    magnitude.push_back(point.magnitude);
    magnitude_db.push_back(point.magnitude_db);
    phase.push_back(point.phase);
  }
  py::dict result;
  result["frequency"] = array_of(frequency);
  result["magnitude"] = array_of(magnitude);
  result["magnitude_db"] = array_of(magnitude_db);
  result["phase"] = array_of(phase);
  return result;
}

const Signal& reference_signal(const PyResult& result, const std::string& channel) {
  const auto slash = channel.rfind('/');
  const auto& system = *result.scenario->system;
  const auto slot = slash == std::string::npos
                        ? std::nullopt
                        : system.signal_slot(channel.substr(0, slash), channel.substr(slash + 1));
  if (!slot)
    throw UsageError("control_task: reference: '" + channel +
                     "' is not a controller's reference signal in '" +
                     result.scenario->settings.name +
                     "' (a pid controller's, or an external one's with target and reference)");
  return *system.signal_slots()[static_cast<std::size_t>(*slot)].signal;
}

py::dict control_task(const PyResult& result, const std::string& reference, const py::object& truth,
                      const py::object& estimate) {
  const Signal& signal = reference_signal(result, reference);
  const RecordChannels channels = memory_record_channels(*result.scenario, *result.run);
  const auto& r = channels.channel(reference);
  const bool force = r.unit == "N";
  const std::string truth_channel =
      truth.is_none() ? (force ? "muscle/force" : "muscle/deflection") : truth.cast<std::string>();
  const std::string estimate_channel = estimate.is_none()
                                           ? (force ? "estimator/force" : "estimator/deflection")
                                           : estimate.cast<std::string>();
  const auto& y = channels.channel(truth_channel);
  if (y.unit != r.unit || y.columns != 1 || r.columns != 1)
    throw UsageError("control_task: truth: '" + truth_channel + "' [" + y.unit +
                     "] is not a scalar in the reference's unit [" + r.unit + "]");
  std::span<const double> estimated;
  if (!estimate_channel.empty()) estimated = channels.channel(estimate_channel).values;

  TaskAnalysis analysis;
  {
    const py::gil_scoped_release released;
    analyse_task(channels.time, r.values, y.values, estimated, signal, analysis);
  }
  py::dict task;
  task["reference"] = reference;
  task["truth"] = truth_channel;
  task["unit"] = r.unit;
  task["start"] = signal.next_breakpoint_after(0.0);  // the reference's first change
  if (!analysis.rises.empty()) task["steps"] = rises_dict(analysis);
  if (!analysis.response.empty()) task["response"] = response_dict(analysis);
  task["bandwidth"] = analysis.bandwidth ? py::cast(*analysis.bandwidth) : py::none();
  task["tracking_error"] = statistics_dict(analysis.tracking_errors);
  if (!analysis.estimation_errors.empty()) {
    task["estimate"] = estimate_channel;
    task["estimation_error"] = statistics_dict(analysis.estimation_errors);
  }
  return task;
}

}  // namespace

void bind_control_task(py::module_& module) {
  module.def("control_task", &control_task, py::arg("result"),
             py::arg("reference") = "controller/reference", py::arg("truth") = py::none(),
             py::arg("estimate") = py::none(),
             "The analysis `tcpmsim control-tasks` makes of a chapter-7 task (section 7.4), on a "
             "run closed by any controller: from the reference's first change on, the 10-90 % "
             "rise time of each step (and its overshoot beyond the new reference, away from the "
             "old, as a fraction of the reference's change), or the sine fits, Bode points and -3 "
             "dB bandwidth of a "
             "stepped sine sweep; the tracking error truth - reference and the estimation error "
             "estimate - truth (count, mean, standard_deviation, half_width_95, rmse). `truth` "
             "and `estimate` default to the muscle's and the estimator's force or deflection, by "
             "the reference's unit; estimate='' leaves the estimation error out. No calibration "
             "run is made: give the run as it was closed.");
}

}  // namespace tcpmsim::python
