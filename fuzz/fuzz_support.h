#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>

namespace tcpmsim::fuzz {

// Runs `parse` on one input. The errors a user may meet (ConfigError and the other located
// input errors, UsageError) are the expected outcome of a malformed input; any other exception
// would reach the user as "internal error" (exit 5), so it aborts, and libFuzzer keeps the
// input as a crash.
void expect_clean_outcome(const std::function<void()>& parse);

std::string text_of(const std::uint8_t* data, std::size_t size);

}  // namespace tcpmsim::fuzz
