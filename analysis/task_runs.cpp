#include "analysis/task_runs.h"

#include <cmath>
#include <vector>

#include "analysis/control_tasks.h"
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

}  // namespace tcpmsim
