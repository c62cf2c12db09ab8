#include "sim/config/config_error.h"

namespace tcpmsim {

std::string SourceLocation::describe() const {
  if (!origin.empty()) return origin;
  if (line <= 0) return file;
  return file + ":" + std::to_string(line) + ":" + std::to_string(column);
}

namespace {
std::string format(const SourceLocation& location, const std::string& key_path,
                   const std::string& problem) {
  std::string message = location.describe() + ": error: ";
  if (!key_path.empty()) message += key_path + ": ";
  return message + problem;
}
}  // namespace

ConfigError::ConfigError(SourceLocation location, std::string key_path, std::string problem)
    : std::runtime_error(format(location, key_path, problem)),
      location_(std::move(location)),
      key_path_(std::move(key_path)),
      problem_(std::move(problem)) {}

}  // namespace tcpmsim
