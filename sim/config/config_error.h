#pragma once

#include <stdexcept>
#include <string>
#include <string_view>

namespace tcpmsim {

// Where a configuration value came from: a file position, or a --set on the command line.
struct SourceLocation {
  std::string file;
  int line = 0;        // 1-based; 0 if unknown
  int column = 0;      // 1-based
  std::string origin;  // non-empty for values from the command line

  std::string describe() const;
};

// `text` fit for a terminal: every control byte (and DEL) written as an escape ("\t", "\x00"),
// so that a message quoting bad input never prints the raw byte.
std::string printable(std::string_view text);

// One clear message about bad input: where, which key, what was expected, what was found.
class ConfigError : public std::runtime_error {
 public:
  ConfigError(SourceLocation location, std::string key_path, std::string problem);
  const SourceLocation& location() const { return location_; }
  const std::string& key_path() const { return key_path_; }
  const std::string& problem() const { return problem_; }

 private:
  SourceLocation location_;
  std::string key_path_;
  std::string problem_;
};

// A command asked to do what it does not do with this input: an analysis given a scenario of
// another kind, a choice on the command line that the input cannot serve. The message names
// the input and says what the command takes; the program exits as for a usage error.
class UsageError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

}  // namespace tcpmsim
