// run_two_rounds (sim/parallel_rounds.h): a first round, a second chosen from its results and
// guessed ahead, the same on any number of threads.
#include <catch2/catch.hpp>

#include <atomic>
#include <mutex>
#include <stdexcept>

#include "sim/parallel_rounds.h"

using namespace tcpmsim;

namespace {

// Tasks 0-5 form the first round; task k's result is k * k. The second round is every task
// 6 + k for a first-round k whose result is at least a quarter of the largest finished: 3, 4
// and 5 in the end (9, 16, 25 against 25), others along the way.
struct Squares {
  std::vector<long> results = std::vector<long>(12, -1);
  std::vector<std::atomic<int>> runs = std::vector<std::atomic<int>>(12);
  std::mutex order_mutex;
  std::vector<std::size_t> order;

  std::vector<std::size_t> second(const std::vector<char>& finished) const {
    long largest = 0;
    for (std::size_t k = 0; k < 6; ++k)
      if (finished[k]) largest = std::max(largest, results[k]);
    std::vector<std::size_t> chosen;
    for (std::size_t k = 0; k < 6; ++k)
      if (finished[k] && 4 * results[k] >= largest && largest > 0) chosen.push_back(6 + k);
    return chosen;
  }
  void run(std::size_t k) {
    ++runs[k];
    {
      std::lock_guard lock(order_mutex);
      order.push_back(k);
    }
    results[k] = k < 6 ? static_cast<long>(k * k) : -static_cast<long>(k);
  }
  std::vector<std::size_t> go(std::size_t lead, int threads) {
    return run_two_rounds(
        {5, 4, 3, 2, 1, 0}, lead, [this](const auto& finished) { return second(finished); }, 12,
        threads, [this](std::size_t k) { run(k); });
  }
};

}  // namespace

TEST_CASE("Two rounds return the second round the first's results choose, on any thread count",
          "[thread]") {
  for (const int threads : {1, 2, 3, 8}) {
    for (const std::size_t lead : {0, 1, 6}) {
      INFO(threads << " threads, lead " << lead);
      Squares squares;
      CHECK(squares.go(lead, threads) == std::vector<std::size_t>{9, 10, 11});
      for (std::size_t k = 0; k < 6; ++k) CHECK(squares.runs[k] == 1);
      for (std::size_t k = 9; k < 12; ++k) {
        CHECK(squares.runs[k] == 1);
        CHECK(squares.results[k] == -static_cast<long>(k));
      }
      // A guess the final choice drops may have run (at most once), never more.
      for (std::size_t k = 6; k < 9; ++k) CHECK(squares.runs[k] <= 1);
    }
  }
}

TEST_CASE(
    "Once its lead is finished, a guessed second-round task goes before the rest of the "
    "first") {
  // One thread: task 5 (25) leads, so 11 (its square is the largest) is guessed at once; the
  // guesses that follow each finished task come before the next first-round one.
  Squares squares;
  CHECK(squares.go(1, 1) == std::vector<std::size_t>{9, 10, 11});
  CHECK(squares.order == std::vector<std::size_t>{5, 11, 4, 10, 3, 9, 2, 1, 0});
  // Led by the whole first round, the second starts only after it, in its chosen order.
  Squares led;
  led.go(6, 1);
  CHECK(led.order == std::vector<std::size_t>{5, 4, 3, 2, 1, 0, 9, 10, 11});
}

TEST_CASE("A task that throws is reported after all threads are done; a dropped guess's is not",
          "[thread]") {
  for (const int threads : {1, 2}) {
    INFO(threads << " threads");
    CHECK_THROWS_WITH(
        run_two_rounds(
            {0, 1, 2}, 0, [](const auto&) { return std::vector<std::size_t>{3}; }, 4, threads,
            [](std::size_t k) {
              if (k == 1) throw std::runtime_error("task 1 failed");
            }),
        "task 1 failed");
    // The guess (task 3) throws, but the final choice, made once 2 has finished, drops it.
    CHECK_NOTHROW(run_two_rounds(
        {0, 1, 2}, 0,
        [](const std::vector<char>& finished) {
          return finished[2] ? std::vector<std::size_t>{} : std::vector<std::size_t>{3};
        },
        4, threads,
        [](std::size_t k) {
          if (k == 3) throw std::runtime_error("a dropped guess");
        }));
  }
}

TEST_CASE("Whatever a task throws is rethrown as it was, once all threads are done") {
  for (const int threads : {1, 2}) {
    INFO(threads << " threads");
    CHECK_THROWS_AS(
        run_two_rounds(
            {0, 1}, 0, [](const auto&) { return std::vector<std::size_t>{}; }, 2, threads,
            [](std::size_t k) {
              if (k == 1) throw 42;
            }),
        int);
    CHECK_THROWS_AS(
        run_two_rounds(
            {0, 1}, 0, [](const auto&) { return std::vector<std::size_t>{}; }, 2, threads,
            [](std::size_t k) {
              if (k == 0) throw std::invalid_argument("");
            }),
        std::invalid_argument);
  }
}

TEST_CASE("A second round that names a first-round task, or fails, stops every thread") {
  for (const int threads : {1, 2}) {
    INFO(threads << " threads");
    std::atomic<int> runs = 0;
    const auto count = [&](std::size_t) { ++runs; };
    // Task 1 would run twice, and the first round would count as done before it is.
    CHECK_THROWS_AS(run_two_rounds(
                        {0, 1, 2}, 0, [](const auto&) { return std::vector<std::size_t>{1}; }, 3,
                        threads, count),
                    std::logic_error);
    CHECK_THROWS_AS(
        run_two_rounds(
            {0}, 0, [](const auto&) { return std::vector<std::size_t>{7}; }, 3, threads, count),
        std::logic_error);
    runs = 0;
    CHECK_THROWS_WITH(run_two_rounds(
                          {0, 1, 2, 3}, 1,
                          [](const std::vector<char>& finished) -> std::vector<std::size_t> {
                            if (finished[0]) throw std::runtime_error("no choice");
                            return {};
                          },
                          5, threads, count),
                      "no choice");
    // On one thread the choice failed as soon as task 0 had finished, and nothing ran after it;
    // on two, the other thread's task may have begun before, and it still ends.
    if (threads == 1) CHECK(runs == 1);
  }
}

TEST_CASE("The first round's ids must be distinct and below the task count") {
  const auto nothing = [](const auto&) { return std::vector<std::size_t>{}; };
  CHECK_THROWS_AS(run_two_rounds({0, 0}, 0, nothing, 2, 1, [](std::size_t) {}),
                  std::invalid_argument);
  CHECK_THROWS_AS(run_two_rounds({0, 2}, 0, nothing, 2, 1, [](std::size_t) {}),
                  std::invalid_argument);
}
