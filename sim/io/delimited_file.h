#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "sim/config/config_error.h"

namespace tcpmsim {

// A located error in an input data file: "file:line:column: error: what was expected, got what".
// It is a ConfigError, so the command line reports it like any other bad input (exit code 3).
class DataFileError : public ConfigError {
 public:
  DataFileError(SourceLocation location, std::string problem)
      : ConfigError(std::move(location), "", std::move(problem)) {}
};

// One field of a delimited text line, trimmed of blanks, with the 1-based column of its first
// character (of the separator position + 1 if the field is empty).
struct TextField {
  std::string text;
  int column = 0;
};

struct TextRow {
  int line = 0;        // 1-based
  int end_column = 0;  // the column just past the line's last character
  std::vector<TextField> fields;
};

// A text table of `separator`-delimited fields (the LCR-meter CSVs use ';'), read whole; blank
// lines are skipped. Numbers are parsed on request with located errors.
class DelimitedFile {
 public:
  static DelimitedFile read(const std::string& path, char separator);
  static DelimitedFile parse(const std::string& text, const std::string& name, char separator);

  const std::string& name() const { return name_; }
  const std::vector<TextRow>& rows() const { return rows_; }

  // The field as a finite number ("+4.0e-06", "12", "-3.5"); `meaning` names it in the error:
  // "file:3:45: error: field 6 (inductance reading 1 [H]): expected a number, got '4.0x-06'".
  double number(const TextRow& row, std::size_t field, std::string_view meaning) const;
  // Requires exactly `count` fields; `layout` describes them in the error.
  void require_fields(const TextRow& row, std::size_t count, std::string_view layout) const;

  [[noreturn]] void fail(int line, int column, const std::string& problem) const;

 private:
  std::string name_;
  char separator_ = ';';
  std::vector<TextRow> rows_;
};

}  // namespace tcpmsim
