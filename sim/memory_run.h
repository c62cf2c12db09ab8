#pragma once

#include <string>
#include <vector>

#include "sim/integrator.h"
#include "sim/io/record_layout.h"
#include "sim/run.h"
#include "sim/scenario.h"

namespace tcpmsim {

// A run kept in memory, laid out as its HDF5 record would be: the output times and, per series
// (/muscle/force; /b/temperature with a column per member), its samples. What the Python module
// returns; its values are the record's, bit for bit (both are handed the same outputs).
struct MemoryRun {
  std::vector<double> time;
  std::vector<RecordSeries> series;
  std::vector<std::vector<double>> values;  // per series: time x columns, row-major
  SolverStatistics statistics;
  double wall_seconds = 0.0;
  // "complete", or "failed" / "interrupted" with the reason and the samples up to `time_reached`.
  std::string status;
  std::string reason;
  double time_reached = 0.0;

  // The series named "group/name" ("muscle/force", "b/drive/power"), or none.
  const RecordSeries* find(const std::string& channel, std::size_t* index = nullptr) const;
};

// Appends every output sample to a MemoryRun laid out by record_layout.
class MemoryRunSink final : public OutputSink {
 public:
  explicit MemoryRunSink(MemoryRun& run);
  void record(double time, std::span<const double> signals) override;

 private:
  MemoryRun& run_;
};

// Integrates `scenario` in a fresh context, keeping every recorded output. A solver failure or a
// StopRequest from `progress` ends the run with that status rather than throwing; the samples
// before it are kept. Before anything is allocated, throws the ConfigError of
// check_record_size (sim/run.h) when the samples would exceed `limit_bytes`, as `tcpmsim run`
// refuses such a record.
MemoryRun run_in_memory(const Scenario& scenario, const Integrator::Progress& progress = {},
                        double limit_bytes = kDefaultRecordLimit);

// Writes `run` (a run of `scenario`) as the record `tcpmsim run` writes: the same datasets,
// inputs, attributes and ending, so that the file is the one a command-line run would leave
// (a failed or interrupted run as <stem>.failed.h5 or .interrupted.h5). Returns the path written.
std::string save_record(const Scenario& scenario, const MemoryRun& run, const std::string& path);
// The same for a run in `context` (its parameters, as a run set them, describe its inputs).
std::string save_record(const Scenario& scenario, const Context& context, const MemoryRun& run,
                        const std::string& path);

}  // namespace tcpmsim
