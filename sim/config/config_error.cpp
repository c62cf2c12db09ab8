#include "sim/config/config_error.h"

namespace tcpmsim {

std::string SourceLocation::describe() const {
  if (!origin.empty()) return origin;
  if (line <= 0) return file;
  return file + ":" + std::to_string(line) + ":" + std::to_string(column);
}

namespace {

// The length of the UTF-8 sequence that starts at text[at] (2 to 4 bytes), or 0 when the bytes
// there are not one (binary garbage, another encoding).
std::size_t utf8_sequence(std::string_view text, std::size_t at) {
  const auto lead = static_cast<unsigned char>(text[at]);
  const std::size_t length = lead >= 0xc2 && lead < 0xe0   ? 2
                             : lead >= 0xe0 && lead < 0xf0 ? 3
                             : lead >= 0xf0 && lead < 0xf5 ? 4
                                                           : 0;
  if (length == 0 || at + length > text.size()) return 0;
  for (std::size_t k = 1; k < length; ++k) {
    if ((static_cast<unsigned char>(text[at + k]) & 0xc0) != 0x80) return 0;
  }
  return length;
}

}  // namespace

// Beside control bytes, a byte of no UTF-8 sequence is escaped too ("\xff"): a binary file
// read as text is never echoed raw.
std::string printable(std::string_view text) {
  static constexpr char kHex[] = "0123456789abcdef";
  std::string result;
  result.reserve(text.size());
  for (std::size_t at = 0; at < text.size(); ++at) {
    const char c = text[at];
    const auto byte = static_cast<unsigned char>(c);
    if (byte >= 0x80) {
      if (const std::size_t length = utf8_sequence(text, at); length > 0) {
        result.append(text.substr(at, length));
        at += length - 1;
        continue;
      }
    }
    if (byte >= 0x20 && byte < 0x7f) {
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
