#include "sim/config/config_error.h"

namespace tcpmsim {

std::string SourceLocation::describe() const {
  if (!origin.empty()) return origin;
  if (line <= 0) return file;
  return file + ":" + std::to_string(line) + ":" + std::to_string(column);
}

std::string printable(std::string_view text) {
  static constexpr char kHex[] = "0123456789abcdef";
  std::string result;
  result.reserve(text.size());
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte >= 0x20 && byte != 0x7f) {
      result += c;
    } else if (c == '\t') {
      result += "\\t";
    } else if (c == '\n') {
      result += "\\n";
    } else if (c == '\r') {
      result += "\\r";
    } else {
      result += "\\x";
      result += kHex[byte >> 4];
      result += kHex[byte & 0xf];
    }
  }
  return result;
}

namespace {
std::string format(const SourceLocation& location, const std::string& key_path,
                   const std::string& problem) {
  std::string message = location.describe() + ": error: ";
  if (!key_path.empty()) message += key_path + ": ";
  return printable(message + problem);
}
}  // namespace

ConfigError::ConfigError(SourceLocation location, std::string key_path, std::string problem)
    : std::runtime_error(format(location, key_path, problem)),
      location_(std::move(location)),
      key_path_(std::move(key_path)),
      problem_(std::move(problem)) {}

}  // namespace tcpmsim
