#pragma once

#include <string>

#include "sim/context.h"
#include "sim/integrator.h"
#include "sim/memory_record.h"
#include "sim/scenario.h"

namespace tcpmsim {

// What the control-task runners (single muscle and pair) share: a run kept in memory, and a
// calibration offset read from it.

// Integrates `scenario` in `context`, keeping every recorded output.
MemoryRecord simulate_in_memory(const Scenario& scenario, Context& context,
                                SolverStatistics* statistics = nullptr);

// The calibration offset (7.3.4), mean(truth - estimate), over the samples with from <= t < to
// whose estimate is known.
double offset_over(const MemoryRecord& record, const std::string& truth,
                   const std::string& estimate, double from, double to);

}  // namespace tcpmsim
