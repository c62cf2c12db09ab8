// Plausible ranges (issue 30): a value of the right dimension but of an implausible size is
// accepted with a located warning that names the typical range and the likely slip.
#include <catch2/catch.hpp>

#include <string>

#include "kinds/standard_kinds.h"
#include "sim/scenario.h"
#include "tests/support/test_support.h"

using namespace tcpmsim;
using namespace tcpmsim::testing;

namespace {

// The chapter-7 muscle of Table 7.2 with one line of its mechanics replaced.
std::string muscle_with(const std::string& mechanics) {
  return "scenario: {name: slip, duration: 10 s}\n"
         "output: {rate: 4 Hz}\n"
         "muscle:\n"
         "  thermal_force: {form: reduced, kappa_P: 7.2e-3 N/J, kappa_c: 0.1316 1/s,\n"
         "                  ambient_temperature: 23 degC}\n"
         "  mechanics: " +
         mechanics +
         "\n"
         "  resistance: 10.18 ohm\n"
         "  inductance: {quantity: measure, lambda_l: 2.81 mm, lambda_x: 28.8 mm, "
         "lambda_0: 0.433}\n"
         "drive: {mode: power, power: 1 W}\n"
         "load: {type: deflection, deflection: 20 mm}\n";
}

Scenario load(const std::string& text, const std::vector<std::string>& overrides = {}) {
  return load_scenario_text(text, "slip.yaml", overrides, shared_units(), standard_kinds());
}

}  // namespace

TEST_CASE("Table 7.2's mechanics lie in their typical ranges: no warning") {
  const Scenario scenario =
      load(muscle_with("{k1: 10.8 mN/mm, k2: 2.7 mN/mm, damping: 4.3 mN*s/mm, "
                       "force_offset: 0.1069 N}"));
  CHECK(scenario.warnings.empty());
}

TEST_CASE("k1 in N/mm where mN/mm was meant warns at its key with the range and the factor") {
  const Scenario scenario =
      load(muscle_with("{k1: 14.04 N/mm, k2: 2.7 mN/mm, damping: 4.3 mN*s/mm, "
                       "force_offset: 0.1069 N}"));
  REQUIRE(scenario.warnings.size() == 1);
  const std::string& warning = scenario.warnings.front();
  CHECK(warning.find("slip.yaml:6:") == 0);  // the line of k1, its column
  CHECK(warning.find(": warning: muscle.mechanics.k1: '14.04 N/mm' is 14040 N/m") !=
        std::string::npos);
  CHECK(warning.find("outside the typical range (0.1 to 5000 N/m)") != std::string::npos);
  CHECK(warning.find("1/1000 of it, 14.04 N/m, would be typical") != std::string::npos);
}

TEST_CASE("A slip downwards and a --set are caught the same way") {
  const std::string table_7_2 =
      muscle_with("{k1: 10.8 mN/mm, k2: 2.7 mN/mm, damping: 4.3 mN*s/mm, force_offset: 0.1069 N}");
  // 10.8 uN/mm is 1000 times too small.
  const Scenario small = load(table_7_2, {"muscle.mechanics.k1=10.8 uN/mm"});
  REQUIRE(small.warnings.size() == 1);
  CHECK(small.warnings.front().find("command line (--set muscle.mechanics.k1=10.8 uN/mm)") == 0);
  CHECK(small.warnings.front().find("1000 times it, 10.8 N/m, would be typical") !=
        std::string::npos);
  // An ambient temperature of 23 K: degC written as K; no factor makes it typical.
  const Scenario cold = load(table_7_2, {"muscle.thermal_force.ambient_temperature=23 K"});
  REQUIRE(cold.warnings.size() == 1);
  CHECK(cold.warnings.front().find("typical range (230 to 600 K)") != std::string::npos);
  CHECK(cold.warnings.front().find("check its unit and its size") != std::string::npos);
}

TEST_CASE("An effect's, a bundle's and a joint's sizes have typical ranges too") {
  const std::string table_7_2 =
      muscle_with("{k1: 10.8 mN/mm, k2: 2.7 mN/mm, damping: 4.3 mN*s/mm, force_offset: 0.1069 N}");
  // A friction element of 20 mN/mm written in N/mm: 20 000 N/m, 1000 times the typical.
  const Scenario slipped =
      load(table_7_2, {"muscle.effects=[{type: hysteresis, stiffness: 20 N/mm, force: 5 mN}]"});
  REQUIRE(slipped.warnings.size() == 1);
  CHECK(slipped.warnings.front().find("muscle.effects[0].stiffness") != std::string::npos);
  CHECK(slipped.warnings.front().find("1/1000 of it, 20 N/m, would be typical") !=
        std::string::npos);
  // A relaxation time in ms where s was meant: 20 ms is typical, so no word; 20 ks for 20 s
  // written with a prefix too many is 1000 times it and within a day, so neither warns. A
  // branch of 20 Ms is.
  const Scenario slow =
      load(table_7_2, {"muscle.effects=[{type: maxwell_branch, stiffness: 1.5 mN/mm, "
                       "time_constant: 20 Ms}]"});
  REQUIRE(slow.warnings.size() == 1);
  CHECK(slow.warnings.front().find("muscle.effects[0].time_constant") != std::string::npos);
  CHECK(slow.warnings.front().find("typical range (0.01 to 100000 s)") != std::string::npos);
}
