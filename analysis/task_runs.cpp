#include "analysis/task_runs.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "analysis/control_tasks.h"
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
  const double start = reference.next_breakpoint_after(0.0);
  const auto first_after = static_cast<std::size_t>(
      std::lower_bound(record.time.begin(), record.time.end(), start - 1e-9) - record.time.begin());
  std::vector<double> time, r, y;
  for (std::size_t k = first_after > 0 ? first_after - 1 : 0; k < record.time.size(); ++k) {
    time.push_back(record.time[k]);
    r.push_back(record[reference_channel][k]);
    y.push_back(record[truth][k]);
    if (!estimate.empty() && record.time[k] >= start - 1e-9)
      analysis.estimation_errors.push_back(record[estimate][k] - y.back());
  }
  if (const auto* sweep = dynamic_cast<const SteppedSineSignal*>(&reference)) {
    analysis.response = sweep_frequency_response(time, r, y, sweep->schedule());
    analysis.bandwidth = bandwidth_3db(analysis.response);
  } else {
    analysis.rises = step_rise_times(time, r, y);
  }
}

}  // namespace tcpmsim
