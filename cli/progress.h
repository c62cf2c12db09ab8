#pragma once

#include <chrono>
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

}  // namespace tcpmsim
