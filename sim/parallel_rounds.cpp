#include "sim/parallel_rounds.h"

#include <algorithm>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>

namespace tcpmsim {

namespace {

// The shared state of one run_two_rounds: which tasks have started and finished, the next task
// of each round, and the second round once it is final. Guarded by `mutex`.
class TwoRounds {
 public:
  using Choice = std::function<std::vector<std::size_t>(const std::vector<char>&)>;
  TwoRounds(const std::vector<std::size_t>& first, std::size_t lead, const Choice& second,
            std::size_t task_count)
      : first_(first),
        lead_(std::min(lead, first.size())),
        second_(second),
        in_first_(task_count, 0),
        started_(task_count, 0),
        finished_(task_count, 0) {
    for (const std::size_t k : first) in_first_[k] = 1;
    for (std::size_t i = 0; i < lead_; ++i) in_first_[first[i]] = 2;
  }

  // The next task for a thread, or nothing once every task it could start has started. Waits
  // while the first round's last tasks run and no task of the second can be guessed.
  std::optional<std::size_t> take(std::unique_lock<std::mutex>& lock) {
    while (true) {
      if (next_first_ < first_.size()) {
        if (lead_done_ == lead_)
          for (const std::size_t k : second_(finished_))
            if (!started_[k]) return start(k);
        return start(first_[next_first_++]);
      }
      if (first_done_ == first_.size()) {
        if (!final_second_) final_second_ = second_(finished_);
        for (const std::size_t k : *final_second_)
          if (!started_[k]) return start(k);
        return std::nullopt;
      }
      for (const std::size_t k : second_(finished_))
        if (!started_[k]) return start(k);
      changed_.wait(lock);
    }
  }

  void finish(std::size_t k) {
    finished_[k] = 1;
    if (in_first_[k]) ++first_done_;
    if (in_first_[k] == 2) ++lead_done_;
    changed_.notify_all();
  }

  const std::vector<std::size_t>& final_second() const { return *final_second_; }

  std::mutex mutex;

 private:
  std::size_t start(std::size_t k) {
    started_[k] = 1;
    return k;
  }

  const std::vector<std::size_t>& first_;
  const std::size_t lead_;
  const Choice& second_;
  std::vector<char> in_first_;  // 1: a task of `first`, 2: one of its lead
  std::vector<char> started_, finished_;
  std::size_t next_first_ = 0, first_done_ = 0, lead_done_ = 0;
  std::optional<std::vector<std::size_t>> final_second_;
  std::condition_variable changed_;
};

}  // namespace

std::vector<std::size_t> run_two_rounds(
    const std::vector<std::size_t>& first, std::size_t lead,
    const std::function<std::vector<std::size_t>(const std::vector<char>& finished)>& second,
    std::size_t task_count, int threads, const std::function<void(std::size_t)>& run) {
  TwoRounds rounds(first, lead, second, task_count);
  std::vector<std::string> errors(task_count);
  auto work = [&] {
    std::unique_lock lock(rounds.mutex);
    while (const auto task = rounds.take(lock)) {
      lock.unlock();
      try {
        run(*task);
      } catch (const std::exception& error) {
        errors[*task] = error.what();
      }
      lock.lock();
      rounds.finish(*task);
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < std::max(1, threads); ++t) pool.emplace_back(work);
  work();
  for (auto& thread : pool) thread.join();
  std::vector<std::size_t> asked = first;
  asked.insert(asked.end(), rounds.final_second().begin(), rounds.final_second().end());
  std::sort(asked.begin(), asked.end());
  for (const std::size_t k : asked)
    if (!errors[k].empty()) throw std::runtime_error(errors[k]);
  return rounds.final_second();
}

}  // namespace tcpmsim
