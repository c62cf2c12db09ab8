#pragma once

#include <chrono>
#include <cstddef>
#include <cstdio>

namespace tcpmsim {

// A single self-overwriting status line on a terminal, refreshed at most ten times a second.
class ProgressLine {
 public:
  ProgressLine(std::FILE* stream, double end_time);
  ~ProgressLine();
  void update(double time, long steps);

 private:
  std::FILE* stream_;
  double end_time_;
  bool active_;
  bool printed_ = false;
  std::chrono::steady_clock::time_point last_;
};

// Progress of a batch (a sweep's runs): on a terminal a bar with the runs done and the time
// left, refreshed in place; in a log (not a terminal) a plain line at every tenth of the runs
// and at least every 30 s, so that a cluster job's output shows where it is.
class BatchProgress {
 public:
  // `label` starts the plain lines: "sweep", "batch".
  BatchProgress(std::FILE* stream, const char* label);
  ~BatchProgress();
  void update(std::size_t done, std::size_t total);

 private:
  std::FILE* stream_;
  const char* label_;
  bool terminal_;
  bool printed_ = false;
  std::size_t first_done_ = 0;  // done when it started (resumed runs), not counted for the rate
  bool started_ = false;
  std::size_t last_done_ = 0;
  bool reported_finish_ = false;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_;
};

}  // namespace tcpmsim
