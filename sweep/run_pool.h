#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <vector>

#include "sweep/sweep_run.h"
#include "sweep/sweep_spec.h"
#include "sweep/sweep_store.h"

namespace tcpmsim::sweep {

// Hands out the slots of the pending runs, one at a time, to whoever asks first: the threads of
// one process, or every rank of an MPI job. Dynamic, because runs differ in cost by orders of
// magnitude.
class RunDispenser {
 public:
  virtual ~RunDispenser() = default;
  // The next slot (an index into the pending runs), or none when all are handed out.
  virtual std::optional<std::size_t> next() = 0;
};

// Runs the slots `dispenser` hands out on `threads` threads, storing each result as soon as it
// is done. `progress` is called from the calling thread with the runs this process has done, a
// few times a second and at the end. An error storing a run stops this process' threads after
// the runs they hold and is rethrown.
void run_slots(const SweepSpec& spec, const SweepStore& store,
               const std::vector<std::size_t>& pending, int threads, RunDispenser& dispenser,
               ScenarioLoader& loader, const std::function<void(std::size_t)>& progress);

}  // namespace tcpmsim::sweep
