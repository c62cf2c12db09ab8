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

BatchProgress::BatchProgress(std::FILE* stream, const char* label)
    : stream_(stream),
      label_(label),
      terminal_(isatty(fileno(stream)) != 0),
      start_(std::chrono::steady_clock::now()),
      last_(start_) {}

BatchProgress::~BatchProgress() {
  if (printed_ && terminal_) std::fputs("\n", stream_);
}

void BatchProgress::update(std::size_t done, std::size_t total) {
  const auto now = std::chrono::steady_clock::now();
  if (!started_) {
    started_ = true;
    first_done_ = done;
  }
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const std::size_t counted = done - first_done_;
  const double left =
      counted > 0 ? elapsed / static_cast<double>(counted) * static_cast<double>(total - done)
                  : 0.0;
  const bool finished = done == total;
  if (terminal_) {
    if (!finished && now - last_ < std::chrono::milliseconds(100)) return;
    constexpr int kWidth = 30;
    const int filled = total > 0 ? static_cast<int>(kWidth * done / total) : kWidth;
    std::fprintf(stream_, "\r\033[K  [%.*s%*s] %zu/%zu runs, %.0f s, %s", filled,
                 "##############################", kWidth - filled, "", done, total, elapsed,
                 counted > 0 ? "" : "");
    if (counted > 0 && !finished) std::fprintf(stream_, "about %.0f s left", left);
    std::fflush(stream_);
    printed_ = true;
  } else {
    const std::size_t tenth = total >= 10 ? total / 10 : 1;
    const bool step = done / tenth != last_done_ / tenth;
    const bool heartbeat = now - last_ >= std::chrono::seconds(30);
    if (printed_ && (finished ? reported_finish_ : !(step || heartbeat))) return;
    reported_finish_ = finished;
    std::fprintf(stream_, "%s: %zu/%zu runs done, %.1f s elapsed", label_, done, total, elapsed);
    if (counted > 0 && !finished) std::fprintf(stream_, ", about %.0f s left", left);
    std::fputs("\n", stream_);
    std::fflush(stream_);
    printed_ = true;
  }
  last_ = now;
  last_done_ = done;
}

}  // namespace tcpmsim
