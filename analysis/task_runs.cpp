#include "analysis/task_runs.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "analysis/control_tasks.h"
#include "analysis/step_response.h"
#include "signals/control_task_signals.h"
#include "sim/run.h"

namespace tcpmsim {

MemoryRecord simulate_in_memory(const Scenario& scenario, Context& context,
                                SolverStatistics* statistics) {
  MemoryRecord record(*scenario.system);
  const auto totals = integrate(scenario, context, record);
  if (statistics) *statistics = totals;
  return record;
}

double offset_over(const MemoryRecord& record, const std::string& truth,
                   const std::string& estimate, double from, double to) {
  std::vector<double> t, e;
  for (std::size_t k = 0; k < record.time.size(); ++k) {
    if (record.time[k] < from || record.time[k] >= to || !std::isfinite(record[estimate][k]))
      continue;
    t.push_back(record[truth][k]);
    e.push_back(record[estimate][k]);
  }
  return calibration_offset(t, e);
}

void add_to(Context& context, const std::string& path, double offset) {
  context.set_parameter(path, context.parameter(path) + offset);
}

void analyse_task(const MemoryRecord& record, const Signal& reference,
                  const std::string& reference_channel, const std::string& truth,
                  const std::string& estimate, TaskAnalysis& analysis) {
  analyse_task(record.time, record[reference_channel], record[truth],
               estimate.empty() ? std::span<const double>() : std::span(record[estimate]),
               reference, analysis);
}

namespace {

// A step's overshoot against its reference (TaskAnalysis::overshoots), over its hold.
double overshoot(const StepRise& rise, std::span<const double> time,
                 std::span<const double> reference, std::span<const double> truth) {
  if (rise.index == 0) return std::numeric_limits<double>::quiet_NaN();
  std::vector<double> held;
  for (std::size_t k = rise.index; k < time.size() && time[k] < rise.step_time + rise.hold; ++k)
    held.push_back(truth[k]);
  return overshoot_fraction(held, reference[rise.index - 1], rise.target);
}

}  // namespace

void analyse_task(std::span<const double> time, std::span<const double> reference_samples,
                  std::span<const double> truth, std::span<const double> estimate,
                  const Signal& reference, TaskAnalysis& analysis) {
  const double start = reference.next_breakpoint_after(0.0);
  const auto first_after = static_cast<std::size_t>(
      std::lower_bound(time.begin(), time.end(), start - 1e-9) - time.begin());
  std::vector<double> t, r, y;
  for (std::size_t k = first_after > 0 ? first_after - 1 : 0; k < time.size(); ++k) {
    t.push_back(time[k]);
    r.push_back(reference_samples[k]);
    y.push_back(truth[k]);
    if (time[k] < start - 1e-9) continue;
    analysis.tracking_errors.push_back(y.back() - r.back());
    if (!estimate.empty()) analysis.estimation_errors.push_back(estimate[k] - y.back());
  }
  if (const auto* sweep = dynamic_cast<const SteppedSineSignal*>(&reference)) {
    analysis.response = sweep_frequency_response(t, r, y, sweep->schedule());
    analysis.bandwidth = bandwidth_3db(analysis.response);
  } else {
    analysis.rises = step_rise_times(t, r, y);
    for (const auto& rise : analysis.rises) analysis.overshoots.push_back(overshoot(rise, t, r, y));
  }
}

}  // namespace tcpmsim
