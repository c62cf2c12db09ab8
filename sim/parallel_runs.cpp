#include "sim/parallel_runs.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <stdexcept>
#include <thread>
#include <vector>

namespace tcpmsim {

void run_in_parallel(std::span<const std::string> labels, int threads,
                     const std::function<void(std::size_t)>& run) {
  std::vector<std::string> errors(labels.size());
  std::atomic<std::size_t> next{0};
  auto work = [&] {
    for (std::size_t k = next++; k < labels.size(); k = next++) {
      try {
        run(k);
      } catch (const std::exception& error) {
        errors[k] = error.what();
      }
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < std::max(1, threads); ++t) pool.emplace_back(work);
  work();
  for (auto& thread : pool) thread.join();
  for (std::size_t k = 0; k < labels.size(); ++k) {
    if (!errors[k].empty()) throw std::runtime_error(labels[k] + ": " + errors[k]);
  }
}

}  // namespace tcpmsim
