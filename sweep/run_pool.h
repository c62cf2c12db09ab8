#pragma once

#include <atomic>
#include <cstddef>
#include <functional>
#include <optional>
#include <vector>

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

// The threads of one process take the slots 0, 1, ... in order.
class CountingDispenser final : public RunDispenser {
 public:
  explicit CountingDispenser(std::size_t count) : count_(count) {}
  std::optional<std::size_t> next() override;

 private:
  std::size_t count_;
  std::atomic<std::size_t> next_{0};
};

// Calls run(slot) for every slot `dispenser` hands out, on up to `threads` threads (at most
// `slots`, the number it will hand out). `progress` is called from the calling thread with the
// slots this process has done, a few times a second and at the end. An exception from `run`
// stops this process' threads after the slots they hold and is rethrown (runs report their own
// failures; what escapes is an error of the whole batch, such as an unwritable file).
void run_slots(std::size_t slots, int threads, RunDispenser& dispenser,
               const std::function<void(std::size_t)>& run,
               const std::function<void(std::size_t)>& progress);

}  // namespace tcpmsim::sweep
