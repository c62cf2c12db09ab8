#include "sweep/sweep_executor.h"

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

#include "sweep/sweep_run.h"
#include "sweep/sweep_store.h"

namespace tcpmsim::sweep {

SweepOutcome run_sweep(const SweepSpec& spec, const SweepOptions& options,
                       std::shared_ptr<const UnitSystem> units, const SweepProgress& progress) {
  const SweepStore store(spec, options.output, options.resume);
  const std::vector<std::size_t> pending = store.pending();
  SweepOutcome outcome;
  outcome.runs = spec.runs.size();
  outcome.resumed = outcome.runs - pending.size();
  outcome.output = store.output();

  ScenarioLoader loader(std::move(units));
  std::atomic<std::size_t> next{0};
  std::size_t done = 0;
  int exited = 0;
  std::exception_ptr failure;  // an I/O error stops the sweep
  std::mutex mutex;
  std::condition_variable changed;
  const auto work = [&] {
    for (;;) {
      const std::size_t slot = next.fetch_add(1);
      if (slot >= pending.size()) {
        const std::lock_guard lock(mutex);
        ++exited;
        changed.notify_all();
        return;
      }
      try {
        store.write(execute_run(spec, pending[slot], loader));
      } catch (...) {
        const std::lock_guard lock(mutex);
        if (!failure) failure = std::current_exception();
        next = pending.size();  // the others finish the run they hold, then stop
      }
      const std::lock_guard lock(mutex);
      ++done;
      changed.notify_all();
    }
  };
  const int threads = std::max(1, std::min<int>(options.threads, static_cast<int>(pending.size())));
  std::vector<std::thread> workers;
  for (int t = 0; t < threads && !pending.empty(); ++t) workers.emplace_back(work);
  {
    std::unique_lock lock(mutex);
    for (;;) {
      const std::size_t finished = done;
      if (progress) {
        lock.unlock();
        progress(outcome.resumed + finished, outcome.runs);
        lock.lock();
      }
      if (exited == static_cast<int>(workers.size())) break;
      changed.wait_for(lock, std::chrono::milliseconds(200));
    }
  }
  for (auto& worker : workers) worker.join();
  if (failure) std::rethrow_exception(failure);
  outcome.failed = store.merge();
  return outcome;
}

}  // namespace tcpmsim::sweep
