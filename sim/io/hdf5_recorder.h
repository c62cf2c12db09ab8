#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "sim/context.h"
#include "sim/integrator.h"
#include "sim/io/record_writer.h"
#include "sim/system.h"

namespace tcpmsim {

// Writes a run to one HDF5 file: /time plus one dataset per output channel, grouped by
// component (/muscle/force, ...), each with a `units` attribute; the members of a bundle share
// one (time x member) dataset per output (/b/temperature, /b/drive/power) with a `members`
// attribute naming the columns, and their fixed facts (/b/centre_x) a value per member; /inputs
// describes every prescribed signal; root attributes carry the version, git commit, resolved
// config, seed and solver statistics. Datasets are chunked (and, if asked, shuffled and
// deflated) and written chunk by chunk, so memory stays bounded however long the run. The file
// is opened at once (an unwritable path fails here, before the run); the rest of the writing
// (attributes, datasets, /inputs, the samples) is done by a thread of the recorder's own while
// the run integrates, at most two buffers behind. The file is
// written as
// "<out>.partial" and renamed to <out> only when complete; a failed run is kept as "<out
// stem>.failed.h5" with status = "failed" and the reason, an interrupted one as "<out
// stem>.interrupted.h5". The samples reach the file within a few seconds of wall time, and the
// file is flushed, so that a run killed outright leaves a .partial that opens (see
// recover_partial_record).
class Hdf5Recorder final : public OutputSink {
 public:
  // The record of a run of `system` in `context` (prepared: its signals are the run's).
  Hdf5Recorder(std::string path, const System& system, const Context& context,
               const RecordMetadata& metadata, std::size_t chunk_samples = 4096);
  ~Hdf5Recorder() override;
  Hdf5Recorder(const Hdf5Recorder&) = delete;
  Hdf5Recorder& operator=(const Hdf5Recorder&) = delete;

  // Buffers the sample; full buffers go to the writer. Throws std::runtime_error if writing
  // failed.
  void record(double time, std::span<const double> signals) override;
  // Writes what is buffered, the statistics, closes and renames to the final path.
  void finish(const SolverStatistics& statistics);
  // Keeps what was written as the failed file; returns its path.
  std::string fail(const std::string& reason, const SolverStatistics& statistics);
  // Keeps what was written, up to `time_reached`, as the interrupted file; returns its path.
  std::string interrupt(const std::string& reason, double time_reached,
                        const SolverStatistics& statistics);

  static std::string failed_path(const std::string& path);
  // "<out stem>.interrupted.h5".
  static std::string interrupted_path(const std::string& path);

 private:
  void hand_over();  // the full buffers to the writer
  void close_with(const RecordEnding& ending, const SolverStatistics& statistics);
  // Hands the buffers over early when this much wall time passed since the last hand-over, so
  // that a slow run's samples reach the file (and its flushes) within seconds.
  static constexpr double kHandOverSeconds = 2.0;
  std::chrono::steady_clock::time_point last_hand_over_;

  std::string path_;
  static constexpr std::size_t kBufferedValues = std::size_t{1} << 20;
  std::vector<std::vector<int>> columns_;     // per dataset, its signals ([0], time: none)
  std::vector<std::vector<double>> buffers_;  // per dataset, rows of its columns ([0] is time)
  std::size_t flush_rows_ = 1;
  std::unique_ptr<RecordWriter> writer_;  // its own thread: the file, the datasets, the writes
};

}  // namespace tcpmsim
