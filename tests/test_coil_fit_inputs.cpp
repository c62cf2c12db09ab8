// Bad coil-spring inputs give one located message: the data file's line and column, or the
// spring file's key, and what was expected.
#include <unistd.h>
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <string>

#include "analysis/coil_fit_analysis.h"
#include "analysis/coil_sequence.h"
#include "sim/io/delimited_file.h"
#include "tests/support/test_support.h"

using namespace tcpmsim;
using namespace tcpmsim::analysis;
using tcpmsim::testing::replaced;

namespace {

// 24 fields: step; requested; pause; position [mm]; then 10 x (R, L).
const std::string kLine1 =
    "1; 10; 0.5; 0.0; +2.70e-01; +4.01e-06; +2.70e-01; +4.01e-06; +2.70e-01; +4.01e-06; "
    "+2.70e-01; +4.01e-06; +2.70e-01; +4.01e-06; +2.70e-01; +4.01e-06; +2.70e-01; +4.01e-06; "
    "+2.70e-01; +4.01e-06; +2.70e-01; +4.01e-06; +2.70e-01; +4.01e-06\n";
const std::string kLine2 =
    "2; 10; 0.5; 5.9; +2.70e-01; +3.83e-06; +2.70e-01; +3.83e-06; +2.70e-01; +3.83e-06; "
    "+2.70e-01; +3.83e-06; +2.70e-01; +3.83e-06; +2.70e-01; +3.83e-06; +2.70e-01; +3.83e-06; "
    "+2.70e-01; +3.83e-06; +2.70e-01; +3.83e-06; +2.70e-01; +3.83e-06\n";

std::string error_of(const std::string& text) {
  try {
    parse_coil_sequence(text, "S9_01.csv", "S9_01");
  } catch (const DataFileError& error) {
    return error.what();
  }
  FAIL("no DataFileError was thrown");
  return {};
}

}  // namespace

TEST_CASE("A well-formed sequence file is read in SI units") {
  const auto sequence = parse_coil_sequence(kLine1 + kLine2 + "\n", "S9_01.csv", "S9_01");
  REQUIRE(sequence.steps() == 2);
  CHECK(sequence.position[1] == Approx(5.9e-3).epsilon(1e-15));
  CHECK(sequence.inductance[1].size() == 10);
  CHECK(sequence.inductance[1][9] == 3.83e-06);
  CHECK(sequence.resistance[0][0] == 0.27);
  CHECK(sequence.without_first(1).position.front() == sequence.position[1]);
}

TEST_CASE("A malformed number names its line, column, field and meaning") {
  // Line 2, field 6 (the first inductance reading) starts at column 29.
  CHECK(error_of(kLine1 + replaced(kLine2, "+3.83e-06", "+3.8x3e-06")) ==
        "S9_01.csv:2:29: error: field 6 (inductance reading 1 [H]): expected a number, got "
        "'+3.8x3e-06'");
  // Field 4 (position) on line 1 starts at column 13.
  CHECK(error_of(replaced(kLine1, "0.0;", "zero;") + kLine2) ==
        "S9_01.csv:1:13: error: field 4 (measured position [mm]): expected a number, got 'zero'");
  CHECK(error_of(kLine1 + replaced(kLine2, "+2.70e-01", "")) ==
        "S9_01.csv:2:18: error: field 5 (resistance reading 1 [ohm]): expected a number, got ''");
}

TEST_CASE("A line with the wrong number of fields says how many were expected") {
  const std::string layout =
      "expected 24 fields separated by ';' (step; requested step; pause; position [mm]; then 10 "
      "pairs of resistance [ohm] and inductance [H]), got ";
  // One field short: the error points just past the end of the line.
  std::string short_line = kLine2.substr(0, kLine2.rfind(';')) + "\n";
  CHECK(error_of(kLine1 + short_line) ==
        "S9_01.csv:2:" + std::to_string(short_line.size()) + ": error: " + layout + "23");
  // One too many: it points at the surplus field.
  const std::string long_line = kLine2.substr(0, kLine2.size() - 1) + "; 7\n";
  CHECK(error_of(kLine1 + long_line) ==
        "S9_01.csv:2:" + std::to_string(kLine2.size() + 2) + ": error: " + layout + "25");
}

TEST_CASE("Positions must increase from line to line") {
  CHECK(error_of(kLine1 + replaced(kLine2, "5.9;", "0.0;")) ==
        "S9_01.csv:2:13: error: field 4 (measured position [mm]): expected a position beyond "
        "the previous step's '0.0', got '0.0'");
}

TEST_CASE("An empty data file is an error at its first line") {
  CHECK(error_of("\n  \n") ==
        "S9_01.csv:1:1: error: expected measurement lines (step; requested step; pause; "
        "position [mm]; then 10 pairs of resistance [ohm] and inductance [H]), got none");
}

TEST_CASE("A spring file's missing data file is reported where the file names it") {
  const auto directory = std::filesystem::temp_directory_path() /
                         ("tcpmsim_coil_fit_inputs_" + std::to_string(getpid()));
  std::filesystem::create_directories(directory);
  const auto spring_file = directory / "spring.yaml";
  std::ofstream(spring_file) << "coil_spring:\n  name: S9\n  wire_diameter: 1 mm\n"
                                "  outer_diameter: 10 mm\n  body_length: 50 mm\n"
                                "  sequences: [S9_01, S9_02]\n";
  std::ofstream(directory / "S9_01.csv")
      << kLine1 << kLine2 << replaced(kLine2, "2; 10; 0.5; 5.9", "3; 10; 0.5; 11.8");
  const CoilSpring spring = load_coil_spring(spring_file.string(), testing::shared_units());
  CHECK(spring.turns == Approx(49.0).epsilon(1e-14));  // (50 mm - 1 mm) / 1 mm
  CHECK(spring.radius() == Approx(4.5e-3).epsilon(1e-14));
  try {
    analyse_coil_springs({spring}, directory.string());
    FAIL("no error for the missing S9_02.csv");
  } catch (const ConfigError& error) {
    CHECK(std::string(error.what()) ==
          spring_file.string() + ":6:22: error: coil_spring.sequences: no data file '" +
              (directory / "S9_02.csv").string() + "' for sequence 'S9_02'");
  }
  std::filesystem::remove_all(directory);
}

TEST_CASE("A spring file's quantities need units and known keys") {
  const auto read = [](const std::string& yaml) -> std::string {
    try {
      CoilSpring::from_config(
          ConfigNode::load_text(yaml, "spring.yaml", {}, testing::shared_units()));
    } catch (const ConfigError& error) {
      return error.what();
    }
    return "no error";
  };
  const std::string valid =
      "coil_spring:\n  name: S9\n  wire_diameter: 1 mm\n  outer_diameter: 10 mm\n"
      "  body_length: 50 mm\n  sequences: [S9_01]\n";
  CHECK(read(valid) == "no error");
  CHECK(read(replaced(valid, "wire_diameter: 1 mm", "wire_diameter: 1"))
            .starts_with("spring.yaml:3:18: error: coil_spring.wire_diameter:"));
  CHECK(read(replaced(valid, "body_length", "body_lenght")) ==
        "spring.yaml:5:3: error: coil_spring.body_lenght: unknown key 'body_lenght' (did you "
        "mean 'body_length'?)");
  CHECK(read(valid + "  calibration: S9_02\n") ==
        "spring.yaml:7:16: error: coil_spring.calibration: expected one of the spring's "
        "sequences, got 'S9_02'");
}
