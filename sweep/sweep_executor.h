#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <string>

#include "sim/config/units.h"
#include "sweep/sweep_spec.h"

namespace tcpmsim::sweep {

struct SweepOptions {
  std::string output;      // the HDF5 file
  int threads = 1;
  bool resume = false;  // finish an interrupted sweep
  std::string invocation = {};  // the command line, written into the summary
};

struct SweepOutcome {
  std::size_t runs = 0;     // in the sweep
  std::size_t resumed = 0;  // found done by --resume
  std::size_t failed = 0;   // recorded with status "failed"
  std::string output;
};

// Called with the runs done so far (of the sweep's total, resumed ones included), from the
// calling thread, at least at the start and end and a few times a second in between.
using SweepProgress = std::function<void(std::size_t done, std::size_t total)>;

// Runs the sweep's pending runs on `threads` threads: one assembled model per scenario, one
// context per run, runs handed out one at a time as threads free up (runs differ in cost by
// orders of magnitude). Each run's result is stored as soon as it is done, so a killed sweep
// resumes where it stopped; the summary is written at the end. Results do not depend on the
// thread count.
SweepOutcome run_sweep(const SweepSpec& spec, const SweepOptions& options,
                       std::shared_ptr<const UnitSystem> units, const SweepProgress& progress = {});

}  // namespace tcpmsim::sweep
