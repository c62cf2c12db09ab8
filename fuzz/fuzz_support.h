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

// A directory of this process under the system's temporary directory, made once, holding a link
// to every file of the source tree's `source_folder` (configs/discover): the files an input's
// file names beside it. Its path.
std::string scratch_directory(const std::string& name, const std::string& source_folder);

// Writes `text` to `path`, replacing it; aborts if it cannot (the fuzzer's own failure).
void write_file(const std::string& path, const std::string& text);

}  // namespace tcpmsim::fuzz
