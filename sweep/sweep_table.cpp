#include "sweep/sweep_table.h"

#include <H5Cpp.h>

#include <algorithm>
#include <mutex>
#include <sstream>
#include <vector>

#include "sim/io/hdf5_files.h"
#include "sim/value_check.h"

namespace tcpmsim::sweep {
namespace {

struct Column {
  std::string header;
  std::vector<std::string> cells;  // by run
};

Column numbers(const H5::H5File& file, const std::string& name, const std::string& unit) {
  Column column{name + (unit.empty() || unit == "1" ? "" : " [" + unit + "]"), {}};
  for (double value : read_doubles(file, "/summary/" + summary_column(name)))
    column.cells.push_back(number_text(value, 6));
  return column;
}

std::vector<Column> read_columns(const SweepSpec& spec, const std::string& output) {
  const std::lock_guard lock(hdf5_mutex());
  const H5::H5File file(output, H5F_ACC_RDONLY);
  std::vector<Column> columns;
  Column ids{"run", {}};
  for (double id : read_doubles(file, "/summary/id")) ids.cells.push_back(number_text(id));
  columns.push_back(std::move(ids));
  for (const auto& axis : spec.axes) {
    if (axis.structural)
      columns.push_back({axis.path, axis.texts});
    else
      columns.push_back(numbers(file, axis.path, axis.unit));
  }
  for (const auto& derived : spec.derived)
    columns.push_back(numbers(file, derived.path, derived.unit));
  for (const auto& metric : spec.metrics)
    columns.push_back(numbers(file, metric.name, metric.unit));
  columns.push_back({"status", read_texts(file, "/summary/status")});
  return columns;
}

}  // namespace

std::string sweep_table(const SweepSpec& spec, const std::string& output, std::size_t rows) {
  const std::vector<Column> columns = read_columns(spec, output);
  const std::size_t runs = columns.front().cells.size();
  std::vector<std::size_t> width;
  for (const auto& column : columns) {
    std::size_t widest = column.header.size();
    for (const auto& cell : column.cells) widest = std::max(widest, cell.size());
    width.push_back(widest);
  }
  std::ostringstream table;
  auto line = [&](auto cell_of) {
    for (std::size_t c = 0; c < columns.size(); ++c) {
      const std::string cell = cell_of(columns[c]);
      table << (c == 0 ? "" : "  ") << cell << std::string(width[c] - cell.size(), ' ');
    }
    table << "\n";
  };
  line([](const Column& column) { return column.header; });
  const std::size_t head = runs <= rows ? runs : rows / 2;
  for (std::size_t run = 0; run < runs; ++run) {
    if (run == head && runs > rows) {
      table << "... " << runs - rows << " runs more (the summary holds every run)\n";
      run = runs - (rows - head);
    }
    line([run](const Column& column) { return column.cells[run]; });
  }
  return table.str();
}

}  // namespace tcpmsim::sweep
