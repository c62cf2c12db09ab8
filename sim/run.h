#pragma once

#include <string>

#include "sim/integrator.h"
#include "sim/scenario.h"

namespace tcpmsim {

struct RunOutcome {
  SolverStatistics statistics;
  double wall_seconds = 0.0;
  std::string output_path;  // the complete file, or the .failed.h5 file
  bool succeeded = false;
  std::string failure;  // the solver's message when it failed
};

// Integrates a scenario over its duration in `context` and hands `sink` the outputs at its
// output times.
SolverStatistics integrate(const Scenario& scenario, Context& context, OutputSink& sink,
                           const Integrator::Progress& progress = {});
// The same in a fresh context with the scenario's parameters.
SolverStatistics integrate(const Scenario& scenario, OutputSink& sink,
                           const Integrator::Progress& progress = {});

// Integrates a scenario and records it to `output_path` (HDF5). A solver failure does not throw:
// it is reported in the outcome and the partial record is kept as a .failed.h5 file. I/O errors
// throw std::runtime_error.
RunOutcome run_scenario(const Scenario& scenario, const std::string& output_path,
                        const Integrator::Progress& progress = {});
RunOutcome run_scenario(const Scenario& scenario, Context& context, const std::string& output_path,
                        const Integrator::Progress& progress = {});

const char* linear_solver_name(LinearSolverKind kind);

}  // namespace tcpmsim
