#pragma once

#include <functional>
#include <span>
#include <string>

namespace tcpmsim {

// Calls run(k) once for every k < labels.size(), on `threads` threads (the caller's among them).
// Each run writes only its own result, so results do not depend on the thread count. Failures
// are collected per run; the first in index order is rethrown as a std::runtime_error prefixed
// with its label ("configs/a.yaml: ...").
void run_in_parallel(std::span<const std::string> labels, int threads,
                     const std::function<void(std::size_t)>& run);

}  // namespace tcpmsim
