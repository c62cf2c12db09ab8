#pragma once

#include <string>

#include "sim/integrator.h"
#include "sim/scenario.h"

namespace tcpmsim {

struct RecordMetadata;  // sim/io/record_writer.h

struct RunOutcome {
  SolverStatistics statistics;
  double wall_seconds = 0.0;
  std::string output_path;  // the complete file, or the .failed.h5 or .interrupted.h5 file
  bool succeeded = false;
  bool interrupted = false;   // ended early by a StopRequest from the progress observer
  double time_reached = 0.0;  // when interrupted
  std::string failure;        // the solver's message when it failed, or the interruption's reason
};

// Integrates a scenario over its duration in `context` and hands `sink` the outputs at its
// output times.
SolverStatistics integrate(const Scenario& scenario, Context& context, OutputSink& sink,
                           const Integrator::Progress& progress = {});
// The same in a fresh context with the scenario's parameters.
SolverStatistics integrate(const Scenario& scenario, OutputSink& sink,
                           const Integrator::Progress& progress = {});

// Integrates a scenario and records it to `output_path` (HDF5). A solver failure does not throw:
// it is reported in the outcome and the partial record is kept as a .failed.h5 file; a
// StopRequest thrown by `progress` keeps it as an .interrupted.h5 file. I/O errors throw
// std::runtime_error, and so does an output path that is not (or cannot become) a regular file,
// before anything is simulated.
RunOutcome run_scenario(const Scenario& scenario, const std::string& output_path,
                        const Integrator::Progress& progress = {});
RunOutcome run_scenario(const Scenario& scenario, Context& context, const std::string& output_path,
                        const Integrator::Progress& progress = {});

// What a scenario's record says about it (name, file, resolved config, seed, solver, output).
RecordMetadata record_metadata(const Scenario& scenario);

// The size of a scenario's record before compression: its output samples (output.start to the
// end at output.rate, and the end) times its columns (time and every recorded channel, a column
// per member of a set), 8 bytes each.
struct RecordSize {
  double samples = 0.0;
  double columns = 0.0;
  double bytes() const { return 8.0 * samples * columns; }
};
RecordSize estimate_record_size(const Scenario& scenario);
// The limit a record (or a run kept in memory) has unless the user raises it: 2 GB.
inline constexpr double kDefaultRecordLimit = 2e9;
// Throws ConfigError at output.rate when the record would exceed `limit_bytes`, naming the
// estimate, the limit and what to change. Every run checks it before it starts: `tcpmsim run`,
// a batch, and a run in memory (sim/memory_run.h, the Python module's).
void check_record_size(const Scenario& scenario, double limit_bytes);
// "2.6 GB", "512 kB" (decimal units).
std::string byte_text(double bytes);

}  // namespace tcpmsim
