#pragma once

#include <H5Cpp.h>

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <exception>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "sim/context.h"
#include "sim/integrator.h"
#include "sim/signal.h"
#include "sim/system.h"

namespace tcpmsim {

struct RecordMetadata {
  std::string scenario_name;
  std::string config_file;
  std::string resolved_config;  // YAML
  std::uint64_t seed = 0;
  double relative_tolerance = 0.0;
  std::string linear_solver;
  double output_interval = 0.0;
  double duration = 0.0;
  int compression_level = 0;  // deflate (with shuffle) at this level; 0: none
  std::string command_line;   // written when known
};

// Everything a record holds besides its samples, read from the system and the context on the
// run's thread, so that the writer never touches the run's objects.
struct RecordPlan {
  struct Series {
    std::string group;
    std::string name;
    std::string unit;
    std::size_t columns = 1;
    std::vector<std::string> members;
  };
  struct Input {
    std::string path;
    std::string unit;
    SignalDescription description;
    std::vector<std::string> members;  // a member set's signal written once
  };
  RecordMetadata metadata;
  std::size_t chunk_samples = 0;
  std::vector<Series> series;  // after /time
  std::vector<MemberSet> member_sets;
  std::vector<Input> inputs;
};

// The plan of a run's record, and each dataset's signals ([0], /time: none) into `columns`.
RecordPlan plan_record(const System& system, const Context& context, const RecordMetadata& metadata,
                       std::size_t chunk_samples, std::vector<std::vector<int>>& columns);

// How a record ended: status "complete", "failed" (reason: the solver's message, written as
// `failure`) or "interrupted" (reason written as `interruption`, with `time_reached`).
struct RecordEnding {
  std::string status;
  std::string reason;
  double time_reached = 0.0;
};

// The root attributes of an ending: status, and failure or interruption and time_reached.
void write_ending(H5::H5Object& root, const RecordEnding& ending);

// The file side of a record, on a thread of its own: it creates what the plan says, then writes
// the buffers handed to it (each dataset's rows, [0] the times) while the run goes on. At most
// two wait, so memory stays bounded. The file is opened by the constructor, so that an
// unwritable path fails before the run.
class RecordWriter {
 public:
  RecordWriter(const std::string& path, std::shared_ptr<const RecordPlan> plan);
  // Drops whatever is still queued (the recorder was not finished).
  ~RecordWriter();
  RecordWriter(const RecordWriter&) = delete;
  RecordWriter& operator=(const RecordWriter&) = delete;

  // Rethrows the writer's failure, if any; waits while two buffers wait.
  void push(std::vector<std::vector<double>> buffers);
  // Writes the last buffers, the ending and the statistics, and closes; rethrows a failure.
  void close(std::vector<std::vector<double>> last, const RecordEnding& ending,
             const SolverStatistics& statistics);

 private:
  void run(const RecordPlan& plan);
  void create(const RecordPlan& plan);
  void write(const std::vector<std::vector<double>>& buffers);
  void close_file();

  H5::H5File file_;
  std::vector<H5::DataSet> datasets_;  // [0] is /time
  std::size_t written_ = 0;

  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<std::vector<std::vector<double>>> queue_;
  bool closing_ = false;   // write the status and close after the queue
  bool aborting_ = false;  // drop everything
  RecordEnding ending_;
  SolverStatistics statistics_;
  // The file is flushed at most kFlushSeconds of wall time after a write, so that a run killed
  // outright leaves a .partial file that opens, with every sample up to the last flush.
  static constexpr double kFlushSeconds = 1.0;
  std::chrono::steady_clock::time_point last_flush_;
  std::exception_ptr error_;
  std::thread thread_;
};

}  // namespace tcpmsim
