#include "cli/progress.h"

#include <unistd.h>

namespace tcpmsim {

ProgressLine::ProgressLine(std::FILE* stream, double end_time)
    : stream_(stream),
      end_time_(end_time),
      active_(isatty(fileno(stream)) != 0),
      last_(std::chrono::steady_clock::now()) {}

ProgressLine::~ProgressLine() {
  if (printed_) std::fputs("\r\033[K", stream_);
}

void ProgressLine::update(double time, long steps) {
  if (!active_) return;
  const auto now = std::chrono::steady_clock::now();
  if (now - last_ < std::chrono::milliseconds(100)) return;
  last_ = now;
  std::fprintf(stream_, "\r\033[K  t = %.6g s of %.6g s (%5.1f %%), %ld steps", time, end_time_,
               100.0 * time / end_time_, steps);
  std::fflush(stream_);
  printed_ = true;
}

}  // namespace tcpmsim
