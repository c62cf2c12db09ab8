#include "sweep/run_pool.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>

namespace tcpmsim::sweep {

std::optional<std::size_t> CountingDispenser::next() {
  const std::size_t slot = next_.fetch_add(1);
  if (slot >= count_) return std::nullopt;
  return slot;
}

void run_slots(std::size_t slots, int threads, RunDispenser& dispenser,
               const std::function<void(std::size_t)>& run,
               const std::function<void(std::size_t)>& progress) {
  std::size_t done = 0;
  int exited = 0;
  std::atomic<bool> stopped{false};
  std::exception_ptr failure;  // an I/O error stops this process
  std::mutex mutex;
  std::condition_variable changed;
  const auto work = [&] {
    for (;;) {
      const auto slot = stopped ? std::nullopt : dispenser.next();
      if (!slot) {
        const std::lock_guard lock(mutex);
        ++exited;
        changed.notify_all();
        return;
      }
      try {
        run(*slot);
      } catch (...) {
        const std::lock_guard lock(mutex);
        if (!failure) failure = std::current_exception();
        stopped = true;  // the others finish the run they hold, then stop
      }
      const std::lock_guard lock(mutex);
      ++done;
      changed.notify_all();
    }
  };
  const int count = std::max(1, std::min<int>(threads, static_cast<int>(slots)));
  std::vector<std::thread> workers;
  for (int t = 0; t < count && slots > 0; ++t) workers.emplace_back(work);
  {
    std::unique_lock lock(mutex);
    for (;;) {
      const std::size_t finished = done;
      if (progress) {
        lock.unlock();
        progress(finished);
        lock.lock();
      }
      if (exited == static_cast<int>(workers.size())) break;
      changed.wait_for(lock, std::chrono::milliseconds(200));
    }
  }
  for (auto& worker : workers) worker.join();
  if (progress) progress(done);  // the last word: every slot of this process counted
  if (failure) std::rethrow_exception(failure);
}

}  // namespace tcpmsim::sweep
