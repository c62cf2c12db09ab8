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

  // The next task for a thread, or nothing once every task it could start has started (or the
  // rounds were abandoned). Waits while the first round's last tasks run and no task of the
  // second can be guessed.
  std::optional<std::size_t> take(std::unique_lock<std::mutex>& lock) {
    while (!abandoned_) {
      if (next_first_ < first_.size()) {
        if (lead_done_ == lead_)
          for (const std::size_t k : chosen())
            if (!started_[k]) return start(k);
        return start(first_[next_first_++]);
      }
      if (first_done_ == first_.size()) {
        if (!final_second_) final_second_ = chosen();
        for (const std::size_t k : *final_second_)
          if (!started_[k]) return start(k);
        return std::nullopt;
      }
      for (const std::size_t k : chosen())
        if (!started_[k]) return start(k);
      changed_.wait(lock);
    }
    return std::nullopt;
  }

  // No thread starts another task: `second` failed.
  void abandon() {
    abandoned_ = true;
    changed_.notify_all();
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

  // `second` for the tasks finished so far; std::logic_error if it names a task of `first` or
  // one beyond the ids (it would run twice, or out of bounds).
  std::vector<std::size_t> chosen() const {
    std::vector<std::size_t> tasks = second_(finished_);
    for (const std::size_t k : tasks)
      if (k >= in_first_.size() || in_first_[k])
        throw std::logic_error("run_two_rounds: the second round names task " + std::to_string(k) +
                               ", which is " +
                               (k >= in_first_.size() ? "beyond the task ids" : "in the first"));
    return tasks;
  }

  const std::vector<std::size_t>& first_;
  const std::size_t lead_;
  const Choice& second_;
  std::vector<char> in_first_;  // 1: a task of `first`, 2: one of its lead
  std::vector<char> started_, finished_;
  std::size_t next_first_ = 0, first_done_ = 0, lead_done_ = 0;
  std::optional<std::vector<std::size_t>> final_second_;
  bool abandoned_ = false;
  std::condition_variable changed_;
};

// std::invalid_argument unless `first` holds distinct ids below `task_count`.
void check_first_round(const std::vector<std::size_t>& first, std::size_t task_count) {
  std::vector<char> seen(task_count, 0);
  for (const std::size_t k : first) {
    if (k >= task_count || seen[k])
      throw std::invalid_argument("run_two_rounds: task " + std::to_string(k) + " of the first " +
                                  (k >= task_count ? "is beyond the task ids" : "appears twice"));
    seen[k] = 1;
  }
}

}  // namespace

std::vector<std::size_t> run_two_rounds(
    const std::vector<std::size_t>& first, std::size_t lead,
    const std::function<std::vector<std::size_t>(const std::vector<char>& finished)>& second,
    std::size_t task_count, int threads, const std::function<void(std::size_t)>& run) {
  check_first_round(first, task_count);
  TwoRounds rounds(first, lead, second, task_count);
  std::vector<std::exception_ptr> errors(task_count);
  std::exception_ptr choice_error;  // from `second`: guarded by rounds.mutex
  auto work = [&] {
    std::unique_lock lock(rounds.mutex);
    while (true) {
      std::optional<std::size_t> task;
      try {
        task = rounds.take(lock);
      } catch (...) {
        if (!choice_error) choice_error = std::current_exception();
        rounds.abandon();
      }
      if (!task) return;
      lock.unlock();
      try {
        run(*task);
      } catch (...) {
        errors[*task] = std::current_exception();
      }
      lock.lock();
      rounds.finish(*task);
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < std::max(1, threads); ++t) pool.emplace_back(work);
  work();
  for (auto& thread : pool) thread.join();
  if (choice_error) std::rethrow_exception(choice_error);
  std::vector<std::size_t> asked = first;
  asked.insert(asked.end(), rounds.final_second().begin(), rounds.final_second().end());
  std::sort(asked.begin(), asked.end());
  for (const std::size_t k : asked)
    if (errors[k]) std::rethrow_exception(errors[k]);
  return rounds.final_second();
}

}  // namespace tcpmsim
