// Optional self-sensing (issue 30): a muscle needs its coil's inductance only when something
// reads it. Without the key the muscle has no inductance output and runs as before; a Muscle
// Drive, which measures the inductance, asks for it at its own section.
#include <catch2/catch.hpp>

#include <string>

#include "tests/support/test_support.h"

using namespace tcpmsim::testing;

namespace {

const std::string kInductanceLine =
    "  inductance: {quantity: measure, lambda_l: 2.81 mm, lambda_x: 28.8 mm, lambda_0: 0.433}\n";

// The physical test muscle under a 1 W Joule drive, without its inductance line.
std::string without_inductance(std::string yaml) {
  const auto at = yaml.find(kInductanceLine);
  REQUIRE(at != std::string::npos);
  return yaml.erase(at, kInductanceLine.size());
}

}  // namespace

TEST_CASE("A muscle without self-sensing keys runs, and its other outputs are unchanged") {
  const std::vector<std::string> heated = {"drive.power=1 W"};
  const Trace with = simulate(physical_muscle_yaml(), heated);
  const Trace without = simulate(without_inductance(physical_muscle_yaml()), heated);
  CHECK(with.channels.count("muscle/inductance_measure") == 1);
  CHECK(without.channels.count("muscle/inductance_measure") == 0);
  CHECK(without.channels.count("muscle/inductance") == 0);
  // The inductance feeds nothing back: every other channel is the same, bit for bit.
  for (const auto& [name, values] : without.channels) {
    INFO(name);
    CHECK(values == with[name]);
  }
  CHECK(without.channels.size() + 1 == with.channels.size());
}

TEST_CASE("A Muscle Drive on a muscle without an inductance asks for it at the drive") {
  std::string yaml = without_inductance(physical_muscle_yaml());
  const std::string joule = "drive: {mode: power, power: 0 W}\n";
  const auto at = yaml.find(joule);
  REQUIRE(at != std::string::npos);
  yaml.replace(at, joule.size(),
               "drive: {model: muscle_drive, mode: power, power: 1 W, supply_voltage: 7 V}\n");
  const std::string message = config_error(yaml);
  CHECK(message.find("drive: the Muscle Drive measures the coil's inductance (self-sensing), "
                     "but muscle states none: give muscle.inductance") != std::string::npos);
}
