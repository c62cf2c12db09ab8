#pragma once

#include <string>
#include <vector>

namespace tcpmsim::analysis {

// One measurement sequence of the chapter-2 experiment: per deflection step the measured
// position and the LCR meter's repeated (resistance, inductance) readings. SI units.
struct CoilSequence {
  std::string name;  // file stem, e.g. "S1_01"
  std::string file;
  std::vector<int> line;                        // source line of each step
  std::vector<int> position_column;             // source column of each step's position
  std::vector<double> position;                 // [m] relative to the free length
  std::vector<std::vector<double>> resistance;  // [ohm] readings per step
  std::vector<std::vector<double>> inductance;  // [H] readings per step

  std::size_t steps() const { return position.size(); }
  // The same sequence without its first `count` steps (the free-length line is dropped).
  CoilSequence without_first(std::size_t count) const;
};

inline constexpr std::size_t kReadingsPerStep = 10;

// Reads a sequence file (see ../shared/data/coil-spring-inductance/README.md): per line
// "step; requested step; pause; position [mm]; R1 [ohm]; L1 [H]; ...; R10; L10", separated by
// ';'. Every malformed line is a DataFileError at file:line:column saying what was expected.
CoilSequence read_coil_sequence(const std::string& file, const std::string& name);
// The same from text (tests); `file` names it in errors.
CoilSequence parse_coil_sequence(const std::string& text, const std::string& file,
                                 const std::string& name);

}  // namespace tcpmsim::analysis
