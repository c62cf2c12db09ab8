#pragma once

#include <stdexcept>
#include <string>

namespace tcpmsim {

// Where a configuration value came from: a file position, or a --set on the command line.
struct SourceLocation {
  std::string file;
  int line = 0;        // 1-based; 0 if unknown
  int column = 0;      // 1-based
  std::string origin;  // non-empty for values from the command line

  std::string describe() const;
};

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

}  // namespace tcpmsim
