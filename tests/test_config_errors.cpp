// Every class of bad input gets one located message: file:line:col, key path, expectation.
#include <catch2/catch.hpp>

#include <array>

#include "sim/config/config_node.h"
#include "sim/config/units.h"
#include "tests/support/test_support.h"

using namespace tcpmsim;
using namespace tcpmsim::testing;

namespace {
// Line numbers below refer to this text (line 1 is "scenario: ...").
const std::string kValid = R"(scenario: {name: test, duration: 10 s}
output: {rate: 10 Hz}
solver: {rtol: 1.0e-6, linear_solver: dense}
muscle:
  thermal:
    heat_capacity: 0.5 J/K
    conductance: 0.05 W/K
    ambient_temperature: 20 degC
  thermal_force: {form: physical, force_per_kelvin: 2 mN/K, reference_temperature: 20 degC}
  mechanics:
    k1: 10 N/m
    k2: 2.5 N/m
    damping: 5 N*s/m
    force_offset: 0.1 N
  resistance: 10 ohm
  inductance: {quantity: measure, lambda_l: 2.81 mm, lambda_x: 28.8 mm, lambda_0: 0.433}
drive: {mode: power, power: 0 W}
load: {type: deflection, deflection: 20 mm}
)";

std::string error_of(const std::string& yaml, const std::vector<std::string>& overrides = {}) {
  const std::string message = config_error(yaml, overrides);
  if (message == "no error") FAIL("no ConfigError was thrown");
  return message;
}
}  // namespace

TEST_CASE("The reference configuration of these tests is valid") {
  CHECK_NOTHROW(scenario_from_text(kValid));
}

TEST_CASE("A misspelt required key is reported as unknown, with the key it should be") {
  CHECK(error_of(replaced(kValid, "    conductance:", "    conductanse:")) ==
        "test.yaml:7:5: error: muscle.thermal.conductanse: unknown key 'conductanse' (did you mean "
        "'conductance'?)");
}

TEST_CASE("A misspelt optional key is reported as unknown, with a suggestion") {
  CHECK(error_of(replaced(
            kValid, "    conductance: 0.05 W/K\n",
            "    conductance: 0.05 W/K\n    radation: {emissivity: 0.9, area: 1 cm^2}\n")) ==
        "test.yaml:8:5: error: muscle.thermal.radation: unknown key 'radation' (did you mean "
        "'radiation'?)");
}

TEST_CASE("An unknown key far from every known one lists the known keys") {
  CHECK(
      error_of(replaced(kValid, "output: {rate: 10 Hz}", "output: {rate: 10 Hz, colour: blue}")) ==
      "test.yaml:2:23: error: output.colour: unknown key 'colour'; known keys here: compression, "
      "compression_level, rate, start");
}

TEST_CASE("A missing key names the section that needs it") {
  // At the section's key (line 10, "  mechanics:"), not the line below it.
  CHECK(error_of(replaced(kValid, "    k1: 10 N/m\n", "")) ==
        "test.yaml:10:3: error: muscle.mechanics: missing required key 'k1'");
}

TEST_CASE("A value of the wrong type says what was expected") {
  CHECK(error_of(replaced(kValid, "k1: 10 N/m", "k1: [10 N/m, 11 N/m]")) ==
        "test.yaml:11:9: error: muscle.mechanics.k1: expected a quantity in N/m, got a sequence");
  CHECK(error_of(replaced(kValid, "k1: 10 N/m", "k1: stiff")) ==
        "test.yaml:11:9: error: muscle.mechanics.k1: expected a quantity in N/m such as '1.5 N/m', "
        "got 'stiff'");
}

TEST_CASE("A quantity in the wrong unit is rejected with both units") {
  CHECK(error_of(replaced(kValid, "k1: 10 N/m", "k1: 10 N")) ==
        "test.yaml:11:9: error: muscle.mechanics.k1: wrong unit in '10 N': unit 'N' cannot be "
        "converted to 'N/m'; expected a stiffness (force/length), e.g. N/m or N/mm");
  CHECK(error_of(replaced(kValid, "k1: 10 N/m", "k1: 10 blorps")) ==
        "test.yaml:11:9: error: muscle.mechanics.k1: wrong unit in '10 blorps': 'blorps' is not a "
        "unit; expected a stiffness (force/length), e.g. N/m or N/mm");
}

TEST_CASE("A unit is never taken for its reciprocal") {
  // udunits alone would invert these: 16 s as a rate of 1/16 Hz, mm/N as a stiffness.
  CHECK(error_of(replaced(kValid, "rate: 10 Hz", "rate: 16 s")) ==
        "test.yaml:2:16: error: output.rate: wrong unit in '16 s': unit 's' cannot be converted "
        "to 'Hz'; expected a frequency (1/time), e.g. Hz or 1/s");
  CHECK(error_of(replaced(kValid, "duration: 10 s", "duration: 400 Hz")) ==
        "test.yaml:1:34: error: scenario.duration: wrong unit in '400 Hz': unit 'Hz' cannot be "
        "converted to 's'; expected a time, e.g. s or ms");
  CHECK(error_of(replaced(kValid, "k1: 10 N/m", "k1: 92.6 mm/N")) ==
        "test.yaml:11:9: error: muscle.mechanics.k1: wrong unit in '92.6 mm/N': unit 'mm/N' cannot "
        "be converted to 'N/m'; expected a stiffness (force/length), e.g. N/m or N/mm");
  CHECK_NOTHROW(scenario_from_text(replaced(kValid, "rate: 10 Hz", "rate: 10 1/s")));
}

TEST_CASE("A dimensional quantity without a unit is rejected") {
  CHECK(error_of(replaced(kValid, "heat_capacity: 0.5 J/K", "heat_capacity: 0.5")) ==
        "test.yaml:6:20: error: muscle.thermal.heat_capacity: '0.5' has no unit; expected a heat "
        "capacity (energy/temperature), e.g. J/K or mJ/K");
}

TEST_CASE("A unit hint names what the key measures, never the bare number in SI (issue 13)") {
  // '10.8e-3 N/m' would pin a number meant in N/mm to N/m, 1000 times off.
  CHECK(error_of(replaced(kValid, "k1: 10 N/m", "k1: 10.8e-3")) ==
        "test.yaml:11:9: error: muscle.mechanics.k1: '10.8e-3' has no unit; expected a stiffness "
        "(force/length), e.g. N/m or N/mm");
  // A temperature: the offset unit first. 'C' is the coulomb.
  CHECK(error_of(replaced(kValid, "ambient_temperature: 20 degC", "ambient_temperature: 23")) ==
        "test.yaml:8:26: error: muscle.thermal.ambient_temperature: '23' has no unit; expected a "
        "temperature, e.g. degC or K");
  CHECK(error_of(replaced(kValid, "ambient_temperature: 20 degC", "ambient_temperature: 23 C")) ==
        "test.yaml:8:26: error: muscle.thermal.ambient_temperature: wrong unit in '23 C': unit "
        "'C' cannot be converted to 'K'; expected a temperature, e.g. degC or K");
  // The hint comes from the expected unit's dimension, however the unit is spelt.
  const UnitSystem& units = *shared_units();
  CHECK(units.describe_dimension("N/m") == "a stiffness (force/length), e.g. N/m or N/mm");
  CHECK(units.describe_dimension("kg/s^2") == "a stiffness (force/length), e.g. N/m or N/mm");
  CHECK(units.describe_dimension("degC") == "a temperature, e.g. degC or K");
  CHECK(units.describe_dimension("1/s") == "a frequency (1/time), e.g. Hz or 1/s");
  CHECK(units.describe_dimension("rad") == "an angle, e.g. rad or deg");
  // A dimension the table does not name keeps the unit itself.
  CHECK(units.describe_dimension("s/H").empty());
  CHECK(error_of(kValid, {"muscle.mechanics.k1=10.8e-3"}) ==
        "command line (--set muscle.mechanics.k1=10.8e-3): error: muscle.mechanics.k1: '10.8e-3' "
        "has no unit; expected a stiffness (force/length), e.g. N/m or N/mm");
}

TEST_CASE("Non-physical values are rejected") {
  CHECK(error_of(replaced(kValid, "heat_capacity: 0.5 J/K", "heat_capacity: -0.5 J/K")) ==
        "test.yaml:6:20: error: muscle.thermal.heat_capacity: expected a positive value in J/K, "
        "got '-0.5 J/K'");
  CHECK(error_of(replaced(kValid, "resistance: 10 ohm", "resistance: 0 ohm")) ==
        "test.yaml:15:15: error: muscle.resistance: expected a positive value in ohm, got '0 ohm'");
  CHECK(error_of(replaced(kValid, "rtol: 1.0e-6", "rtol: 0")) ==
        "test.yaml:3:16: error: solver.rtol: expected a value in [1e-14, 0.1], got '0'");
  CHECK(error_of(
            replaced(kValid, "ambient_temperature: 20 degC", "ambient_temperature: -300 degC")) ==
        "test.yaml:8:26: error: muscle.thermal.ambient_temperature: the ambient temperature must "
        "stay above 0 K");
  CHECK(error_of(replaced(
            kValid, "drive: {mode: power, power: 0 W}",
            "drive: {mode: duty, supply_voltage: 7 V, series_resistance: 0.57 ohm, duty: 1.2}")) ==
        "test.yaml:17:77: error: drive.duty: the duty cycle reaches 1.200000; it must stay in [0, "
        "1]");
}

TEST_CASE("A choice outside its options suggests the nearest one") {
  CHECK(error_of(replaced(kValid, "linear_solver: dense", "linear_solver: dens")) ==
        "test.yaml:3:39: error: solver.linear_solver: expected one of dense, band, klu, gmres, got "
        "'dens' "
        "(did you mean 'dense'?)");
  // With any linear solver, not only with KLU (where the default is read with the others).
  CHECK(error_of(replaced(kValid, "linear_solver: dense", "linear_solver: dense, restart: warn")) ==
        "test.yaml:3:55: error: solver.restart: expected one of cold, warm, got 'warn' "
        "(did you mean 'warm'?)");
}

TEST_CASE("Broken YAML is reported at its position") {
  CHECK(error_of(replaced(kValid, "output: {rate: 10 Hz}", "output: {rate: 10 Hz")) ==
        "test.yaml:2:9: error: invalid YAML: unclosed flow mapping '{' opened here");
  CHECK(error_of(replaced(kValid, "  mechanics:\n", "  mechanics:\n   bad indentation\n")) ==
        "test.yaml:12:7: error: invalid YAML: illegal map value");
}

TEST_CASE("A bracket or quote never closed is reported where it opens (issue 13)") {
  // yaml-cpp gives up lines later ("end of sequence flow not found" at the next section).
  CHECK(error_of(replaced(kValid, "k1: 10 N/m", "k1: [10 N/m")) ==
        "test.yaml:11:9: error: invalid YAML: unclosed flow sequence '[' opened here");
  // Its closing quote is taken from a later string, whose text then follows it ("end of map not
  // found" far below).
  CHECK(error_of(replaced(replaced(kValid, "resistance: 10 ohm", "resistance: \"10 ohm"),
                          "{mode: power,", "{mode: \"power\",")) ==
        "test.yaml:15:15: error: invalid YAML: unterminated quoted string opened here");
  // yaml-cpp takes a single-quoted string that runs to the end of the file for a string.
  CHECK(error_of(replaced(kValid, "resistance: 10 ohm", "resistance: '10 ohm")) ==
        "test.yaml:15:15: error: invalid YAML: unterminated quoted string opened here");
  CHECK(error_of(replaced(kValid, "resistance: 10 ohm", "resistance: \"10 ohm")) ==
        "test.yaml:15:15: error: invalid YAML: unterminated quoted string opened here");
  // A closing bracket of the other kind closes nothing.
  CHECK(error_of(replaced(kValid, "output: {rate: 10 Hz}", "output: {rate: 10 Hz]")) ==
        "test.yaml:2:9: error: invalid YAML: unclosed flow mapping '{' opened here (']' at 2:21 "
        "does not close it)");
  // A path with an index inside a flow mapping: its ']' closes nothing, and the message says
  // what to write instead.
  CHECK(error_of(replaced(kValid, "output: {rate: 10 Hz}",
                          "output: {rate: 10 Hz, of: muscle.effects[0].force}")) ==
        "test.yaml:2:9: error: invalid YAML: unclosed flow mapping '{' opened here (']' at 2:43 "
        "does not close it); inside {...} or [...] a path with an index needs quotes: "
        "\"muscle.effects[0].force\"");
  // Quotes and brackets in comments and inside plain text open nothing.
  CHECK(error_of(replaced(replaced(kValid, "heat_capacity: 0.5 J/K",
                                   "heat_capacity: 0.5 J/K  # it's [not \"open"),
                          "k1: 10 N/m", "k1: [10 N/m")) ==
        "test.yaml:11:9: error: invalid YAML: unclosed flow sequence '[' opened here");
  CHECK(error_of(
            replaced(replaced(kValid, "heat_capacity: 0.5 J/K", "heat_capacity: it's a[1] \"test"),
                     "k1: 10 N/m", "k1: [10 N/m")) ==
        "test.yaml:11:9: error: invalid YAML: unclosed flow sequence '[' opened here");
}

TEST_CASE("A duplicated key is an error, not a silent overwrite") {
  // At the second, with its full key path and where the first is (issue 13).
  CHECK(error_of(replaced(kValid, "    k2: 2.5 N/m\n", "    k2: 2.5 N/m\n    k2: 3 N/m\n")) ==
        "test.yaml:13:5: error: muscle.mechanics.k2: duplicate key 'k2' (first given at 12:5)");
  CHECK(error_of(replaced(kValid, "power: 0 W}", "power: 0 W, mode: duty}")) ==
        "test.yaml:17:34: error: drive.mode: duplicate key 'mode' (first given at 17:9)");
}

TEST_CASE("Errors in command-line overrides point at the --set") {
  CHECK(error_of(kValid, {"muscle.mechanics.k1=ten"}) ==
        "command line (--set muscle.mechanics.k1=ten): error: muscle.mechanics.k1: expected a "
        "quantity in N/m "
        "such as '1.5 N/m', got 'ten'");
  CHECK(error_of(kValid, {"muscle.mechanics.k3=1 N/m"}) ==
        "command line (--set muscle.mechanics.k3=1 N/m): error: muscle.mechanics.k3: unknown key "
        "'k3' (did you mean 'k1'?)");
  CHECK(error_of(kValid, {"muscle.mechanics.k1"}) ==
        "command line (--set muscle.mechanics.k1): error: expected --set key.path=value");
  // A key path with an empty name: only dots, a leading, trailing or doubled dot (issue 13: a
  // path of dots crashed).
  for (const std::string key : {".", "...", ".muscle", "muscle.", "muscle..mechanics.k1", "[0]"}) {
    INFO(key);
    CHECK(error_of(kValid, {key + "=3"}) ==
          "command line (--set " + key +
              "=3): error: expected --set key.path=value, the key path names joined by '.' (e.g. "
              "muscle.mechanics.k1); '" +
              key + "' has an empty name");
  }
}

TEST_CASE("A --set of null removes the key or element it names; one that names nothing fails") {
  // A section removed: the muscle without its coil law runs, and publishes no inductance.
  const Trace without_coil = simulate(kValid, {"muscle.inductance=null"});
  CHECK(without_coil.channels.count("muscle/inductance_measure") == 0);
  CHECK(simulate(kValid).channels.count("muscle/inductance_measure") == 1);
  CHECK(bitwise_equal(without_coil["muscle/force"],
                      simulate(replaced(kValid,
                                        "  inductance: {quantity: measure, lambda_l: 2.81 mm, "
                                        "lambda_x: 28.8 mm, lambda_0: 0.433}\n",
                                        ""))["muscle/force"]));
  // An element of a list removed: the effects that follow it move up.
  const std::string two_effects = replaced(
      kValid, "  resistance: 10 ohm\n",
      "  resistance: 10 ohm\n  effects: [{type: maxwell_branch, stiffness: 3 N/m, time_constant: "
      "20 s}, {type: hysteresis, stiffness: 50 N/m, force: 6 mN}]\n");
  const std::string second_only = replaced(
      kValid, "  resistance: 10 ohm\n",
      "  resistance: 10 ohm\n  effects: [{type: hysteresis, stiffness: 50 N/m, force: 6 mN}]\n");
  const std::string ramp =
      "drive.power={type: ramp, start_time: 1 s, end_time: 8 s, from: 0 W, "
      "to: 0.2 W}";
  CHECK(bitwise_equal(simulate(two_effects, {"muscle.effects[0]=null", ramp})["muscle/force"],
                      simulate(second_only, {ramp})["muscle/force"]));
  CHECK_FALSE(bitwise_equal(simulate(two_effects, {ramp})["muscle/force"],
                            simulate(second_only, {ramp})["muscle/force"]));
  // A required key removed is missing at the --set that removed it; `~` is null too.
  CHECK(error_of(kValid, {"muscle.mechanics.k1=~"}) ==
        "command line (--set muscle.mechanics.k1=~): error: muscle.mechanics: missing required "
        "key 'k1' (this --set removed it)");
  // A path that names nothing is no silent no-op: a misspelt key gets a suggestion.
  CHECK(error_of(kValid, {"muscle.inductanse=null"}) ==
        "command line (--set muscle.inductanse=null): error: muscle.inductanse: there is nothing "
        "at 'muscle.inductanse' to remove (did you mean 'inductance'?); --set KEY=null removes a "
        "key or an element that is there");
  CHECK(error_of(kValid, {"muscle.effects[0]=null"}) ==
        "command line (--set muscle.effects[0]=null): error: muscle.effects[0]: there is nothing "
        "at 'muscle.effects' to remove; --set KEY=null removes a key or an element that is there");
  CHECK(error_of(two_effects, {"muscle.effects[2]=null"}) ==
        "command line (--set muscle.effects[2]=null): error: muscle.effects[2]: index [2] does not "
        "name an existing element");
  // Null only when spelt out: a value of blanks is a missing value.
  CHECK(error_of(kValid, {"muscle.mechanics.k1= "}) ==
        "command line (--set muscle.mechanics.k1= ): error: muscle.mechanics.k1: expected a value "
        "after '='");
  // A value that is no mapping, read as one, says what it got, with its article.
  CHECK(error_of(kValid, {"muscle.mechanics=[1, 2]"}) ==
        "command line (--set muscle.mechanics=[1, 2]): error: muscle.mechanics: expected a mapping "
        "with key 'k1', got a sequence");
}

TEST_CASE("A deflection that reaches the inductance law's singularity is rejected") {
  CHECK(error_of(replaced(kValid, "deflection: 20 mm}", "deflection: -30 mm}")) ==
        "test.yaml:18:38: error: load.deflection: the deflection reaches -0.030000 m, at or below "
        "-lambda_x = "
        "-0.028800 m where the inductance law (6.3) is singular");
}

TEST_CASE("Inconsistent model choices are explained") {
  const std::string reduced =
      replaced(replaced(kValid,
                        "  thermal_force: {form: physical, force_per_kelvin: "
                        "2 mN/K, reference_temperature: 20 degC}\n",
                        "  thermal_force: {form: reduced, kappa_P: 4e-3 N/J, "
                        "kappa_c: 0.1 1/s, ambient_temperature: 20 degC}\n"),
               "  thermal:\n    heat_capacity: 0.5 J/K\n    conductance: "
               "0.05 W/K\n    ambient_temperature: 20 degC\n",
               "");
  CHECK_NOTHROW(scenario_from_text(reduced));
  CHECK(error_of(replaced(
            reduced, "resistance: 10 ohm",
            "resistance: {form: thermal, resistance: 10 ohm, temperature_coefficient: 6.41e-3 1/K, "
            "reference_temperature: 20 degC}")) ==
        "test.yaml:11:15: error: muscle.resistance: depends on temperature, but the reduced "
        "thermal form reports "
        "none; give muscle.thermal_force.force_per_kelvin");
  CHECK(error_of(replaced(
            kValid, "form: physical, force_per_kelvin: 2 mN/K, reference_temperature: 20 degC",
            "form: reduced, kappa_P: 4e-3 N/J, kappa_c: 0.1 1/s, ambient_temperature: 20 degC")) ==
        "test.yaml:5:3: error: muscle.thermal: the reduced thermal form (7.1) has no thermal node; "
        "remove "
        "muscle.thermal or use thermal_force.form: physical");
}

TEST_CASE("A missing file is named") {
  CHECK_THROWS_WITH(ConfigNode::load_file("/nonexistent/scenario.yaml", {}, shared_units()),
                    "/nonexistent/scenario.yaml: error: cannot open the file for reading");
}

TEST_CASE("YAML aliases that expand without bound are refused at their place (issue 13)") {
  // The "billion laughs": seven levels of ten aliases each would be 10^7 values.
  std::string laughs = "a0: &a0 [lol, lol, lol, lol, lol, lol, lol, lol, lol, lol]\n";
  for (int level = 1; level < 7; ++level) {
    const std::string name = std::string("a").append(std::to_string(level));
    const std::string below = std::string("*a").append(std::to_string(level - 1));
    laughs += name + ": &" + name + " [";
    for (int k = 0; k < 10; ++k) {
      if (k > 0) laughs += ", ";
      laughs += below;
    }
    laughs += "]\n";
  }
  CHECK_THAT(error_of(kValid + laughs),
             Catch::StartsWith("test.yaml:") &&
                 Catch::Contains("error: the document expands to more than 1000000 values (are "
                                 "YAML aliases nested in one another, or referring to "
                                 "themselves?); a configuration needs neither"));
  // A key that is itself a sequence is no name.
  CHECK_THAT(error_of(kValid + "? [a, b]\n: 3\n"),
             Catch::Contains("error: expected a key name, got a sequence"));
}

TEST_CASE("An empty file is reported as such at its start, not as a missing section (issue 13)") {
  for (const std::string text : {"", "\n\n   \n", "# only\n  # comments\n", "---\n"}) {
    INFO(text);
    CHECK_THAT(error_of(text),
               Catch::StartsWith("test.yaml:1:1: error: the file is empty (or holds only "
                                 "comments); expected a mapping with 'scenario' and any of its "
                                 "other sections (") &&
                   Catch::Contains("output") && Catch::Contains("muscle"));
  }
}

TEST_CASE("A key of another variant of a section names the variants that take it (issue 13)") {
  // A hanging mass's key under a load of type deflection: not a misspelling of itself.
  CHECK(error_of(replaced(kValid, "deflection: 20 mm}", "deflection: 20 mm, mass: 35 g}")) ==
        "test.yaml:18:45: error: load.mass: 'mass' is not used with type: deflection; it belongs "
        "to type: hanging_mass (type: deflection takes bundle, deflection, load_cell_resolution, "
        "muscle, muscles)");
  // Every variant that takes it.
  CHECK_THAT(
      error_of(replaced(kValid, "deflection: 20 mm}", "deflection: 20 mm, damping: 1 N*s/m}")),
      Catch::Contains("load.damping: 'damping' is not used with type: deflection; it "
                      "belongs to type: hanging_mass or joint ("));
  // A misspelling is matched against this variant's keys only: 'mass' is none of them.
  CHECK(error_of(replaced(kValid, "deflection: 20 mm}", "deflection: 20 mm, mas: 35 g}")) ==
        "test.yaml:18:45: error: load.mas: unknown key 'mas'; known keys here: bundle, "
        "deflection, load_cell_resolution, muscle, muscles, type");
  // Parts read by other kinds too: a reduced thermal force's key under the physical form.
  CHECK_THAT(error_of(replaced(kValid, "reference_temperature: 20 degC}",
                               "reference_temperature: 20 degC, kappa_c: 0.1 1/s}")),
             Catch::StartsWith("test.yaml:9:") &&
                 Catch::Contains("muscle.thermal_force.kappa_c: 'kappa_c' is not used with form: "
                                 "physical; it belongs to form: reduced (form: physical takes "));
  // The same from the command line, located at the --set.
  CHECK(error_of(kValid, {"load.mass=1 kg"}) ==
        "command line (--set load.mass=1 kg): error: load.mass: 'mass' is not used with type: "
        "deflection; it belongs to type: hanging_mass (type: deflection takes bundle, "
        "deflection, load_cell_resolution, muscle, muscles)");
}

TEST_CASE("Every error about a key a --set introduced names that --set (issue 13)") {
  // The section 'foo' exists only because the --set wrote it: the file has no part in it.
  CHECK_THAT(error_of(kValid, {"foo.bar=1"}),
             Catch::StartsWith("command line (--set foo.bar=1): error: foo: unknown key 'foo'; "
                               "known keys here: "));
  CHECK(error_of(kValid, {"muscle.mechanics.colour.red=1"}) ==
        "command line (--set muscle.mechanics.colour.red=1): error: muscle.mechanics.colour: "
        "unknown key 'colour'; known keys here: damping, force_offset, k1, k2");
  // A section a --set adds is the --set's when it lacks a key, too.
  CHECK(error_of(kValid, {"drives.d2.muscle=muscle"}) ==
        "command line (--set drives.d2.muscle=muscle): error: drives.d2: missing required key "
        "'mode'");
  // A key the file has stays the file's.
  CHECK(error_of(replaced(kValid, "output: {rate: 10 Hz}", "output: {rate: 10 Hz, colour: blue}"),
                 {"foo=1"}) ==
        "test.yaml:2:23: error: output.colour: unknown key 'colour'; known keys here: compression, "
        "compression_level, rate, start");
}

TEST_CASE("A control byte in a file is refused where it is, and never printed raw (issue 13)") {
  const std::string nul(1, '\0');
  // In a value (yaml-cpp said "unknown escape character"), in a comment (accepted), at the end.
  CHECK(error_of(replaced(kValid, "name: test", "name: te" + nul + "st")) ==
        "test.yaml:1:20: error: the file holds a NUL byte (binary or corrupted?)");
  CHECK(error_of(replaced(kValid, "  mechanics:\n", "  mechanics:  # k" + nul + "\n")) ==
        "test.yaml:10:18: error: the file holds a NUL byte (binary or corrupted?)");
  CHECK(error_of(kValid + nul) ==
        "test.yaml:19:1: error: the file holds a NUL byte (binary or corrupted?)");
  CHECK(error_of(replaced(kValid, "name: test", "name: te\x01st")) ==
        "test.yaml:1:20: error: the file holds the control character \\x01 (binary or "
        "corrupted?)");
  // Tabs, carriage returns and line feeds are text.
  CHECK(config_error(replaced(kValid, "k1: 10 N/m", "k1: 10 N/m  # a\tb\r")) == "no error");
  // Any message quoting input escapes what a terminal would act on.
  CHECK(std::string(ConfigError({"f.yaml", 1, 2, {}}, "a\x1b[31m", "got '\x07\t'").what()) ==
        "f.yaml:1:2: error: a\\x1b[31m: got '\\x07\\t'");
  CHECK(printable(std::string("ok \x7f") + '\0') == "ok \\x7f\\x00");
  // Issue 31: bytes of no UTF-8 sequence (binary garbage in a CSV) are escaped; UTF-8 stays.
  CHECK(printable("23 \xc2\xb0"
                  "C, 5 \xc2\xb5m \xff\xfe\xe2\x82") ==
        "23 \xc2\xb0"
        "C, 5 \xc2\xb5m \\xff\\xfe\\xe2\\x82");
}

TEST_CASE("A unit's SI base form: exponents of kg m s A K mol cd rad, a factor and an offset") {
  const UnitSystem& units = *shared_units();
  using E = std::array<int, 8>;
  CHECK(units.si_base("W").exponents == E{1, 2, -3, 0, 0, 0, 0, 0});
  CHECK(units.si_base("N/m").exponents == E{1, 0, -2, 0, 0, 0, 0, 0});
  CHECK(units.si_base("H").exponents == E{1, 2, -2, -2, 0, 0, 0, 0});
  CHECK(units.si_base("1").exponents == E{});
  CHECK(units.si_base("rad").exponents == E{0, 0, 0, 0, 0, 0, 0, 1});
  // value [base] = factor * value [unit] + offset: 1 mN = 1e-3 N, 20 degC = 293.15 K.
  const SiBaseUnit millinewton = units.si_base("mN");
  CHECK(millinewton.exponents == E{1, 1, -2, 0, 0, 0, 0, 0});
  CHECK(millinewton.factor == Approx(1e-3).epsilon(1e-15));
  CHECK(millinewton.offset == 0.0);
  const SiBaseUnit celsius = units.si_base("degC");
  CHECK(celsius.exponents == E{0, 0, 0, 0, 1, 0, 0, 0});
  CHECK(celsius.factor == 1.0);
  CHECK(celsius.offset == Approx(273.15).epsilon(1e-15));
  CHECK(units.si_base("furlong/fortnight").exponents == E{0, 1, -1, 0, 0, 0, 0, 0});
  CHECK_THROWS_AS(units.si_base("quux"), UnitError);
}

TEST_CASE("A difference (a noise, a spread) converts without the units' offsets") {
  const UnitSystem& units = *shared_units();
  CHECK(units.convert_difference(0.5, "degC", "K") == 0.5);
  CHECK(units.convert_difference(0.5, "K", "degC") == 0.5);
  CHECK(units.convert(0.5, "degC", "K") == Approx(273.65).epsilon(1e-15));  // a temperature
  CHECK(units.convert_difference(9.0, "degF", "K") == Approx(5.0).epsilon(1e-15));
  // Between units without an offset it is the value's conversion to the bit.
  CHECK(units.convert_difference(2.0, "mN", "N") == units.convert(2.0, "mN", "N"));
  CHECK_THROWS_AS(units.convert_difference(1.0, "degC", "N"), UnitError);
  // In a configuration: a key read as a difference, beside one read as a value.
  const ConfigNode root =
      ConfigNode::load_text("noise: 0.5 degC\nlevel: 0.5 degC\n", "t.yaml", {}, shared_units());
  CHECK(root.difference("noise", "K") == 0.5);
  CHECK(root.quantity("level", "K") == Approx(273.65).epsilon(1e-15));
  CHECK(root.difference_or("missing", "K", 0.1) == 0.1);
}

TEST_CASE("A scenario that does not assemble is reported at the section that caused it") {
  const std::string muscle = R"(scenario: {name: t, duration: 1 s}
output: {rate: 10 Hz}
muscles:
  m:
    thermal_force: {form: reduced, kappa_P: 7.2e-3 N/J, kappa_c: 131.6e-3 1/s, ambient_temperature: 23 degC}
    mechanics: {k1: 10.8 N/m, k2: 2.7 N/m, damping: 4.3 N*s/m, force_offset: 0.1 N}
    resistance: 10 ohm
    inductance: {quantity: measure, lambda_l: 2.81 mm, lambda_x: 28.8 mm, lambda_0: 0.433}
load: {type: force, force: 0.4 N}
)";
  // Two drives heat one muscle: at the second drive's section, naming both.
  CHECK(error_of(muscle + "drives:\n  a: {mode: power, power: 1 W, muscle: m}\n"
                          "  b: {mode: power, power: 1 W, muscle: m}\n") ==
        "test.yaml:12:6: error: drives.b: the scenario does not assemble: m/reduced_thermal_force "
        "input 'power' takes one source, but 2 are connected; from drives.a, drives.b");
  // Nothing heats the muscle: at the muscle's key, not at the top of the file nor a line below.
  CHECK(error_of(muscle) ==
        "test.yaml:4:3: error: muscles.m: the scenario does not assemble: "
        "m/reduced_thermal_force input 'power' is not connected");
}
