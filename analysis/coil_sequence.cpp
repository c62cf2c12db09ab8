#include "analysis/coil_sequence.h"

#include "sim/io/delimited_file.h"

namespace tcpmsim::analysis {

namespace {

constexpr std::size_t kLeadingFields = 4;
constexpr std::size_t kFields = kLeadingFields + 2 * kReadingsPerStep;
constexpr const char* kLayout =
    "step; requested step; pause; position [mm]; then 10 pairs of resistance [ohm] and "
    "inductance [H]";

CoilSequence from_table(const DelimitedFile& table, const std::string& name) {
  CoilSequence sequence;
  sequence.name = name;
  sequence.file = table.name();
  if (table.rows().empty()) {
    table.fail(1, 1, "expected measurement lines (" + std::string(kLayout) + "), got none");
  }
  for (const TextRow& row : table.rows()) {
    table.require_fields(row, kFields, kLayout);
    table.number(row, 0, "step number");
    table.number(row, 1, "requested position step");
    table.number(row, 2, "pause time");
    const double position_mm = table.number(row, 3, "measured position [mm]");
    std::vector<double> resistance, inductance;
    for (std::size_t k = 0; k < kReadingsPerStep; ++k) {
      const std::size_t field = kLeadingFields + 2 * k;
      const std::string reading = "reading " + std::to_string(k + 1);
      resistance.push_back(table.number(row, field, "resistance " + reading + " [ohm]"));
      inductance.push_back(table.number(row, field + 1, "inductance " + reading + " [H]"));
    }
    if (!sequence.position.empty() && !(position_mm * 1e-3 > sequence.position.back())) {
      const std::string& previous = table.rows()[sequence.steps() - 1].fields[3].text;
      table.fail(row.line, row.fields[3].column,
                 "field 4 (measured position [mm]): expected a position beyond the previous "
                 "step's '" +
                     previous + "', got '" + row.fields[3].text + "'");
    }
    sequence.line.push_back(row.line);
    sequence.position_column.push_back(row.fields[3].column);
    sequence.position.push_back(position_mm * 1e-3);
    sequence.resistance.push_back(std::move(resistance));
    sequence.inductance.push_back(std::move(inductance));
  }
  return sequence;
}

}  // namespace

CoilSequence CoilSequence::without_first(std::size_t count) const {
  CoilSequence kept;
  kept.name = name;
  kept.file = file;
  for (std::size_t i = count; i < steps(); ++i) {
    kept.line.push_back(line[i]);
    kept.position_column.push_back(position_column[i]);
    kept.position.push_back(position[i]);
    kept.resistance.push_back(resistance[i]);
    kept.inductance.push_back(inductance[i]);
  }
  return kept;
}

CoilSequence read_coil_sequence(const std::string& file, const std::string& name) {
  return from_table(DelimitedFile::read(file, ';'), name);
}

CoilSequence parse_coil_sequence(const std::string& text, const std::string& file,
                                 const std::string& name) {
  return from_table(DelimitedFile::parse(text, file, ';'), name);
}

}  // namespace tcpmsim::analysis
