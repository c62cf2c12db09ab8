// Sizes a run would need, and geometry and data a model cannot take, are refused where they are
// written, before anything is allocated or simulated (issue 13): the message names the key, the
// value and the limit.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <string>

#include "analysis/coil_fit_analysis.h"
#include "analysis/coil_spring.h"
#include "sim/config/config_error.h"
#include "tests/support/test_support.h"

using namespace tcpmsim;
using namespace tcpmsim::testing;

namespace {

std::string with_power(const std::string& signal) {
  return replaced(physical_muscle_yaml(), "drive: {mode: power, power: 0 W}",
                  "drive: {mode: power, power: " + signal + "}");
}

// A chapter-4 coil spring between imposed ends, with Maxwell's inductance sensor.
std::string spring_yaml(const std::string& windings, const std::string& range) {
  return R"(scenario: {name: spring, duration: 0.01 s}
output: {rate: 10 kHz}
solver: {method: adams, rtol: 1.0e-8}
spring:
  windings: )" +
         windings + R"(
  rest_length: 81 mm
  mass: 80 g
  stiffness: 9100 N/m
  first_end: {type: sine, offset: 0 mm, amplitude: 0.04 mm, frequency: 168.634 Hz}
  second_end: 102 mm
  inductance:
    coil_radius: 8 mm
    wire_diameter: 3.2 mm
    operating_range: )" +
         range + "\n";
}

}  // namespace

TEST_CASE("The reference spring of these tests is valid") {
  CHECK_NOTHROW(scenario_from_text(spring_yaml("25", "[82 mm, 122 mm]")));
}

TEST_CASE("A multisine of more components than a run can sum is refused with the limit") {
  const std::string message = config_error(with_power(
      "{type: multisine, components: 1000000000000, band: [0.01 Hz, 1 Hz], offset: 0.1 W, "
      "amplitude: 0.05 W}"));
  CHECK_THAT(message, Catch::StartsWith("test.yaml:") &&
                          Catch::Contains("drive.power.components") &&
                          Catch::Contains("1000000000000") && Catch::Contains("1e+06") &&
                          Catch::Contains("sums each component"));
  // Within the int range and still absurd: the same refusal, not an allocation of gigabytes.
  CHECK_THAT(config_error(with_power("{type: multisine, components: 1000000000, band: [0.01 Hz, "
                                     "1 Hz], offset: 0.1 W, amplitude: 0.05 W}")),
             Catch::Contains("drive.power.components") && Catch::Contains("1000000000"));
}

TEST_CASE("A multisine whose range would take hours to find is refused at its band") {
  // Issue 31: a band up to 1e9 Hz hung `validate` in the scan for the signal's extrema, which
  // scaling to a range and every check of a drive's signal over the run make.
  CHECK_THAT(config_error(with_power("{type: multisine, components: 10, band: [0.01 Hz, 1e9 Hz], "
                                     "range: [0 W, 1 W], duration: 100 s}")),
             Catch::StartsWith("test.yaml:") &&
                 Catch::Contains("error: drive.power.band: finding the signal's range scans "
                                 "1.6e+12 points (16 per period of the band's upper end over 100 "
                                 "s) of 10 components = 1.6e+13 terms, over the limit of 1e+08"));
  CHECK_THAT(config_error(with_power("{type: multisine, components: 10, band: [0.01 Hz, 1e9 Hz], "
                                     "offset: 0.5 W, amplitude: 0.05 W}")),
             Catch::Contains("error: drive.power.band: finding the signal's range scans"));
  CHECK(config_error(with_power("{type: multisine, components: 10, band: [0.01 Hz, 1 kHz], "
                                "range: [0.1 W, 1 W], duration: 100 s}")) == "no error");
}

TEST_CASE("A random-step sequence of more samples than memory holds is refused at sample_rate") {
  const std::string message =
      config_error(with_power("{type: random_steps, range: [0 W, 1 W], process_time_constant: "
                              "20 s, sample_rate: 1e12 Hz}"));
  CHECK_THAT(message, Catch::Contains("drive.power.sample_rate") && Catch::Contains("1e+14") &&
                          Catch::Contains("1e+08"));
}

TEST_CASE("A spring of more windings than a run can integrate is refused with the limit") {
  CHECK_THAT(config_error(spring_yaml("1000000000", "[82 mm, 122 mm]")),
             Catch::StartsWith("test.yaml:5:") && Catch::Contains("spring.windings") &&
                 Catch::Contains("1000000000") && Catch::Contains("10000"));
}

TEST_CASE(
    "A coil whose windings would overlap is refused at operating_range, with the solid "
    "length") {
  // 25 windings of 3.2 mm wire: 80 mm solid.
  CHECK_THAT(config_error(spring_yaml("25", "[0.01 mm, 0.05 mm]")),
             Catch::StartsWith("test.yaml:14:") &&
                 Catch::Contains("spring.inductance.operating_range") &&
                 Catch::Contains("solid length") && Catch::Contains("0.08 m"));
  CHECK_THAT(
      config_error(spring_yaml("25", "[82 mm, 122 mm]"), {"spring.inductance.wire_diameter=5 m"}),
      Catch::Contains("spring.inductance.coil_radius") && Catch::Contains("wire does not fit"));
  // The same check when a run sets the geometry (a sweep over the wire diameter).
  const Scenario scenario = scenario_from_text(spring_yaml("25", "[82 mm, 122 mm]"));
  Context context = scenario.make_context();
  context.set_parameter("spring.inductance.wire_diameter", 3.5e-3);  // 87.5 mm solid
  CHECK_THROWS_WITH(scenario.system->prepare(context), Catch::Contains("windings would overlap"));
}

TEST_CASE("Spring data placing the coil at a negative length is refused at its line and column") {
  namespace fs = std::filesystem;
  const fs::path directory = process_directory("negative_coil");
  const std::string source = source_path("data/coil-spring-inductance/S1_01.csv");
  std::ifstream in(source);
  REQUIRE(in);
  std::ofstream out(directory / "S1_01.csv");
  std::string line;
  while (std::getline(in, line)) {
    // Every position (field 4) moved 500 mm down: increasing still, but no coil is that short.
    std::size_t field_start = 0;
    for (int separators = 0; separators < 3; ++separators)
      field_start = line.find(';', field_start) + 1;
    const std::size_t field_end = line.find(';', field_start);
    const double position = std::stod(line.substr(field_start, field_end - field_start));
    line = line.substr(0, field_start) + " " + std::to_string(position - 500.0) +
           line.substr(field_end);
    out << line << "\n";
  }
  out.close();
  const std::vector<analysis::CoilSpring> springs{
      analysis::load_coil_spring(source_path("configs/springs/s1.yaml"), shared_units())};
  CHECK_THROWS_WITH(analysis::analyse_coil_springs(springs, directory.string()),
                    Catch::Contains("S1_01.csv:1:") && Catch::Contains("field 4") &&
                        Catch::Contains("expected a position above"));
}
