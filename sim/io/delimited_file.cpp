#include "sim/io/delimited_file.h"

#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace tcpmsim {

namespace {

bool is_blank(char c) {
  return c == ' ' || c == '\t' || c == '\r';
}

}  // namespace

DelimitedFile DelimitedFile::read(const std::string& path, char separator) {
  // A directory opens as a stream on Linux and reads as empty: say what it is.
  if (std::filesystem::is_directory(path))
    throw DataFileError({path, 0, 0, {}}, "it is a directory, not a data file");
  std::ifstream stream(path, std::ios::binary);
  if (!stream) throw DataFileError({path, 0, 0, {}}, "cannot open the file for reading");
  std::stringstream buffer;
  buffer << stream.rdbuf();
  return parse(buffer.str(), path, separator);
}

DelimitedFile DelimitedFile::parse(const std::string& text, const std::string& name,
                                   char separator) {
  DelimitedFile file;
  file.name_ = name;
  file.separator_ = separator;
  int line_number = 0;
  std::size_t start = 0;
  while (start <= text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    const std::string_view line(text.data() + start, end - start);
    ++line_number;
    if (line.find_first_not_of(" \t\r") != std::string_view::npos) {
      TextRow row;
      row.line = line_number;
      std::size_t content_end = line.size();
      while (content_end > 0 && is_blank(line[content_end - 1])) --content_end;
      row.end_column = static_cast<int>(content_end) + 1;
      std::size_t field_start = 0;
      while (true) {
        std::size_t field_end = line.find(separator, field_start);
        if (field_end == std::string_view::npos) field_end = line.size();
        std::size_t first = field_start, last = field_end;
        while (first < last && is_blank(line[first])) ++first;
        while (last > first && is_blank(line[last - 1])) --last;
        row.fields.push_back(
            {std::string(line.substr(first, last - first)), static_cast<int>(first) + 1});
        if (field_end == line.size()) break;
        field_start = field_end + 1;
      }
      file.rows_.push_back(std::move(row));
    }
    if (end == text.size()) break;
    start = end + 1;
  }
  return file;
}

void DelimitedFile::fail(int line, int column, const std::string& problem) const {
  throw DataFileError({name_, line, column, {}}, problem);
}

void DelimitedFile::require_fields(const TextRow& row, std::size_t count,
                                   std::string_view layout) const {
  if (row.fields.size() == count) return;
  const std::string expected = "expected " + std::to_string(count) + " fields separated by '" +
                               std::string(1, separator_) + "' (" + std::string(layout) +
                               "), got " + std::to_string(row.fields.size());
  // Too many: point at the first surplus field; too few: at the end of the line.
  const int column = row.fields.size() > count ? row.fields[count].column : row.end_column;
  fail(row.line, column, expected);
}

double DelimitedFile::number(const TextRow& row, std::size_t field,
                             std::string_view meaning) const {
  const TextField& text = row.fields.at(field);
  std::string_view digits = text.text;
  if (!digits.empty() && digits.front() == '+') digits.remove_prefix(1);  // from_chars rejects '+'
  double value = 0.0;
  const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  const bool signs_doubled =
      text.text.size() > 1 && text.text[0] == '+' && (text.text[1] == '-' || text.text[1] == '+');
  const bool parsed = !digits.empty() && error == std::errc() &&
                      end == digits.data() + digits.size() && !signs_doubled;
  if (parsed && !std::isfinite(value)) {
    fail(row.line, text.column,
         "field " + std::to_string(field + 1) + " (" + std::string(meaning) +
             "): expected a finite number, got '" + text.text + "'");
  }
  if (!parsed) {
    fail(row.line, text.column,
         "field " + std::to_string(field + 1) + " (" + std::string(meaning) +
             "): expected a number, got '" + text.text + "'");
  }
  return value;
}

}  // namespace tcpmsim
