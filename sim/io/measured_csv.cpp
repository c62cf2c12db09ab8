// Measured data from comma-separated text: "time[s],power[W],deflection[mm],force[N]".
#include <cmath>
#include <functional>
#include <sstream>

#include "sim/config/config_node.h"
#include "sim/io/measured_data.h"

namespace tcpmsim {

namespace {

// A header's column: what it measures, and how its values become SI.
struct Column {
  std::string name;
  std::string unit;
  const MeasuredQuantity* quantity = nullptr;
  std::function<double(double)> to_si;
};

bool is_comment(const TextRow& row) {
  return !row.fields.empty() && !row.fields.front().text.empty() &&
         row.fields.front().text.front() == '#';
}

bool is_identifier(std::string_view word) {
  if (word.empty() || std::isdigit(static_cast<unsigned char>(word.front()))) return false;
  for (char c : word) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_') return false;
  }
  return true;
}

// Whether a channel name is "quantity" or "instance.quantity" (an instance of any depth).
bool well_formed(std::string_view name) {
  std::size_t start = 0;
  while (true) {
    const std::size_t dot = name.find('.', start);
    if (!is_identifier(name.substr(start, dot - start))) return false;
    if (dot == std::string_view::npos) return true;
    start = dot + 1;
  }
}

std::string quantity_names() {
  std::string names;
  for (const auto& quantity : measured_quantities()) {
    names += (names.empty() ? "" : ", ") + std::string(quantity.name);
  }
  return names;
}

std::string unknown_channel(std::string_view name) {
  std::vector<std::string> candidates;
  for (const auto& quantity : measured_quantities()) candidates.emplace_back(quantity.name);
  const auto dot = name.rfind('.');
  const std::string_view base = dot == std::string_view::npos ? name : name.substr(dot + 1);
  std::string problem = "unknown channel '" + std::string(name) + "'";
  const std::string suggestion = closest_match(base, candidates);
  if (!suggestion.empty()) {
    problem += " (did you mean '" +
               (dot == std::string_view::npos ? "" : std::string(name.substr(0, dot + 1))) +
               suggestion + "'?)";
  }
  return problem + "; a channel is one of " + quantity_names() +
         ", optionally after an instance's name (left.force)";
}

Column read_column(const DelimitedFile& file, const TextRow& row, const TextField& field,
                   const UnitSystem& units) {
  const std::string& text = field.text;
  const auto open = text.find('[');
  if (text.empty() || open == std::string::npos || text.back() != ']' ||
      text.find(']') != text.size() - 1) {
    file.fail(row.line, field.column,
              "expected a column heading name[unit] such as force[N], got '" + text + "'");
  }
  Column column;
  column.name = text.substr(0, open);
  while (!column.name.empty() && (column.name.back() == ' ' || column.name.back() == '\t'))
    column.name.pop_back();
  if (!well_formed(column.name)) {
    file.fail(
        row.line, field.column,
        "expected a channel name before '[' (a quantity such as force, or left.force), got '" +
            column.name + "'");
  }
  column.quantity = measured_quantity_of(column.name);
  if (!column.quantity) file.fail(row.line, field.column, unknown_channel(column.name));
  if (column.quantity->name == "time" && column.name != "time") {
    file.fail(row.line, field.column,
              "the time column is shared: write 'time', not '" + column.name + "'");
  }
  const int unit_column = field.column + static_cast<int>(open) + 1;
  column.unit = text.substr(open + 1, text.size() - open - 2);
  const std::string expected =
      std::string(column.quantity->what) + ", e.g. " + std::string(column.quantity->examples);
  if (column.unit.find_first_not_of(" \t") == std::string::npos) {
    file.fail(row.line, unit_column,
              "channel '" + column.name + "' has no unit; expected " + expected +
                  " (write [1] for a dimensionless channel)");
  }
  try {
    column.to_si = units.converter(column.unit, column.quantity->si_unit);
  } catch (const UnitError&) {
    const bool known = units.convertible(column.unit, column.unit);
    file.fail(row.line, unit_column,
              known
                  ? "unit '" + column.unit + "' of channel '" + column.name + "' is not " + expected
                  : "'" + column.unit + "' is not a unit; expected " + expected);
  }
  return column;
}

std::vector<Column> read_header(const DelimitedFile& file, const TextRow& header,
                                const UnitSystem& units) {
  std::vector<Column> columns;
  for (std::size_t k = 0; k < header.fields.size(); ++k) {
    columns.push_back(read_column(file, header, header.fields[k], units));
    for (std::size_t j = 0; j < k; ++j) {
      if (columns[j].name == columns[k].name) {
        file.fail(header.line, header.fields[k].column,
                  "channel '" + columns[k].name + "' appears twice (columns " +
                      std::to_string(j + 1) + " and " + std::to_string(k + 1) + ")");
      }
    }
  }
  if (columns.front().name != "time") {
    file.fail(header.line, header.fields.front().column,
              "the first column must be time, e.g. time[s],power[W],force[N]; got '" +
                  columns.front().name + "'");
  }
  return columns;
}

std::string layout_of(const std::vector<Column>& columns) {
  std::string layout = "one per heading:";
  for (const auto& column : columns) layout += " " + column.name;
  return layout;
}

// The row's values in SI, each checked against its quantity's physical range.
void read_row(const DelimitedFile& file, const TextRow& row, const std::vector<Column>& columns,
              std::vector<std::vector<double>>& values) {
  file.require_fields(row, columns.size(), layout_of(columns));
  for (std::size_t k = 0; k < columns.size(); ++k) {
    const Column& column = columns[k];
    const double value = column.to_si(file.number(row, k, column.name + " [" + column.unit + "]"));
    if (value < column.quantity->lowest || value > column.quantity->highest) {
      std::ostringstream range;
      range << column.quantity->lowest << " to " << column.quantity->highest << " "
            << column.quantity->si_unit;
      file.fail(row.line, row.fields[k].column,
                column.name + " '" + row.fields[k].text + "' [" + column.unit +
                    "] is outside the physical range " + range.str());
    }
    values[k].push_back(value);
  }
}

void check_time_increases(const DelimitedFile& file, const std::vector<const TextRow*>& rows,
                          const std::vector<double>& time) {
  for (std::size_t k = 1; k < time.size(); ++k) {
    if (time[k] > time[k - 1]) continue;
    const std::string previous =
        seconds_text(time[k - 1]) + " on line " + std::to_string(rows[k - 1]->line);
    file.fail(rows[k]->line, rows[k]->fields.front().column,
              time[k] == time[k - 1]
                  ? "duplicate time: " + seconds_text(time[k]) + " repeats " + previous
                  : "time goes back: " + seconds_text(time[k]) + " after " + previous +
                        "; sample times must increase strictly");
  }
}

MeasuredData from_table(const DelimitedFile& file, const UnitSystem& units) {
  std::vector<const TextRow*> rows;
  for (const auto& row : file.rows()) {
    if (!is_comment(row)) rows.push_back(&row);
  }
  if (rows.empty()) {
    file.fail(1, 1,
              "the file holds no header; expected a first line naming each column as "
              "name[unit], e.g. time[s],power[W],force[N]");
  }
  const std::vector<Column> columns = read_header(file, *rows.front(), units);
  rows.erase(rows.begin());
  if (rows.empty()) {
    file.fail(file.rows().back().line + 1, 1, "no data rows after the header");
  }
  std::vector<std::vector<double>> values(columns.size());
  for (auto& column : values) column.reserve(rows.size());
  for (const TextRow* row : rows) read_row(file, *row, columns, values);
  check_time_increases(file, rows, values.front());
  std::vector<MeasuredChannel> channels;
  for (std::size_t k = 1; k < columns.size(); ++k) {
    channels.push_back({columns[k].name, std::string(columns[k].quantity->si_unit), columns[k].unit,
                        std::move(values[k])});
  }
  return MeasuredData(file.name(), std::move(values.front()), std::move(channels));
}

}  // namespace

MeasuredData read_measured_csv(const std::string& path, const UnitSystem& units) {
  return from_table(DelimitedFile::read(path, ','), units);
}

MeasuredData parse_measured_csv(const std::string& text, const std::string& name,
                                const UnitSystem& units) {
  return from_table(DelimitedFile::parse(text, name, ','), units);
}

}  // namespace tcpmsim
