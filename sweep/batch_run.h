#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "sim/config/units.h"
#include "sim/run.h"

namespace tcpmsim::sweep {

// A batch of ready scenario files (tcpmsim run configs/*.yaml --jobs 2), on the sweeps' run pool.
struct BatchOptions {
  std::vector<std::string> configs;
  std::vector<std::string> overrides;  // --set, for every file
  std::string output_directory = "results";
  int threads = 1;
  // Each record's limit (check_record_size), before any run.
  double max_record_bytes = kDefaultRecordLimit;
  std::string invocation = {};  // the command line, written into each record
};

struct BatchRun {
  std::string config;
  RunOutcome outcome;  // its record (or .failed.h5) and statistics
};

// Reads every file first (a bad one is a ConfigError before any run; two files naming the same
// scenario, whose records would collide, are one too), then runs them on `threads` threads,
// each into <output_directory>/<scenario name>.h5. A solver failure is that run's outcome; the
// others go on. `progress` as for sweeps: runs done, of all.
std::vector<BatchRun> run_batch(const BatchOptions& options,
                                std::shared_ptr<const UnitSystem> units,
                                const std::function<void(std::size_t, std::size_t)>& progress = {});

}  // namespace tcpmsim::sweep
