#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace tcpmsim {

// A construct the text opens and never closes: a flow sequence '[', a flow mapping '{' or a
// quoted string. yaml-cpp reports these where it gives up (often many lines later, or as
// "end of map not found"); this says where they were opened.
struct UnclosedConstruct {
  int line = 0;         // 1-based, where the construct opens
  int column = 0;       // 1-based
  std::string what;     // "unclosed flow sequence '[' opened here", ...
  bool to_end = false;  // still open at the end of the text
};

// The construct of a YAML text that is opened and never closed, if any, found by a scan that
// honours comments, quotes and block scalars: a quote or bracket counts only where a value may
// start (so "it's" and "a[1]" in plain scalars open nothing). A quoted string that runs over
// lines and closes where no value may end (the next string's opening quote, followed by its
// text) counts as unterminated.
std::optional<UnclosedConstruct> find_unclosed(std::string_view text);

}  // namespace tcpmsim
