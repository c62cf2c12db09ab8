// Measured data: CSV files with name[unit] headings and tcpmsim records read into SI, every
// class of bad file refused with one located message, and any input replayed from a column.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <H5Cpp.h>

#include "signals/data_signal.h"
#include "sim/io/measured_data.h"
#include "sim/random_stream.h"
#include "sim/run.h"
#include "tests/support/test_support.h"

using namespace tcpmsim;
using namespace tcpmsim::testing;

namespace {

std::string data_error(const std::string& text) {
  try {
    parse_measured_csv(text, "run.csv", *shared_units());
  } catch (const ConfigError& error) {
    return error.what();
  }
  FAIL("no error for:\n" << text);
  return "";
}

// A directory of its own for a test's scenario and data files.
std::filesystem::path fresh_directory(const std::string& name) {
  const auto directory = std::filesystem::temp_directory_path() / "tcpmsim_tests" / name;
  std::filesystem::remove_all(directory);
  std::filesystem::create_directories(directory);
  return directory;
}

void write(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path) << text;
}

// The test muscle (C = 0.5 J/K, hA = 0.05 W/K) with its power replayed by `power_signal`,
// written as a scenario file in `directory`.
std::string replay_scenario(const std::filesystem::path& directory,
                            const std::string& power_signal) {
  const auto path = directory / "replay.yaml";
  write(path, replaced(physical_muscle_yaml(), "power: 0 W", "power: " + power_signal));
  return path.string();
}

std::string scenario_error(const std::string& file,
                           const std::vector<std::string>& overrides = {}) {
  try {
    load_scenario(file, overrides, shared_units());
  } catch (const ConfigError& error) {
    return error.what();
  }
  FAIL("no error");
  return "";
}

}  // namespace

TEST_CASE("A CSV file's columns are converted from the units its headings state into SI") {
  const MeasuredData data = parse_measured_csv(
      "# bench run 3\n"
      "time[ms],power[mW],deflection[mm],force[mN],decay_time[us],temperature[degC],"
      "duty[%],inductance[uH],left.force[N]\n"
      "0,1500,20,107,52.5,23,15,6.5,0.1\n"
      "62.5,1490,20.5,108,52.7,23.5,85,6.4,0.2\n",
      "run.csv", *shared_units());
  CHECK(data.time() == std::vector<double>{0.0, 0.0625});
  const auto value = [&](const std::string& name, std::size_t k) {
    REQUIRE(data.find(name) != nullptr);
    return data.find(name)->values.at(k);
  };
  CHECK(value("power", 0) == Approx(1.5).epsilon(1e-15));
  CHECK(value("deflection", 1) == Approx(0.0205).epsilon(1e-15));
  CHECK(value("force", 0) == Approx(0.107).epsilon(1e-15));
  CHECK(value("decay_time", 1) == Approx(52.7e-6).epsilon(1e-15));
  CHECK(value("temperature", 1) == Approx(296.65).epsilon(1e-15));
  CHECK(value("duty", 1) == Approx(0.85).epsilon(1e-15));
  CHECK(value("inductance", 0) == Approx(6.5e-6).epsilon(1e-15));
  CHECK(value("left.force", 1) == 0.2);
  CHECK(data.find("force")->unit == "N");
  CHECK(data.find("force")->file_unit == "mN");
}

TEST_CASE("A bad data file is refused with its file, line and column and what was expected") {
  SECTION("an empty file, or one of comments only") {
    CHECK(data_error("") ==
          "run.csv:1:1: error: the file holds no header; expected a first line naming each "
          "column as name[unit], e.g. time[s],power[W],force[N]");
    CHECK(data_error("# nothing yet\n\n") == data_error(""));
  }
  SECTION("a header without data") {
    CHECK(data_error("time[s],force[N]\n") == "run.csv:2:1: error: no data rows after the header");
  }
  SECTION("a heading that is not name[unit]") {
    CHECK(data_error("time[s],force\n0,1\n") ==
          "run.csv:1:9: error: expected a column heading name[unit] such as force[N], got "
          "'force'");
    CHECK(data_error("time[s],force[]\n0,1\n") ==
          "run.csv:1:15: error: channel 'force' has no unit; expected a force, e.g. N, mN (write "
          "[1] for a dimensionless channel)");
  }
  SECTION("time must come first") {
    CHECK(data_error("force[N],time[s]\n1,0\n") ==
          "run.csv:1:1: error: the first column must be time, e.g. time[s],power[W],force[N]; "
          "got 'force'");
  }
  SECTION("an unknown channel, with the nearest known one") {
    CHECK(data_error("time[s],forse[N]\n0,1\n") ==
          "run.csv:1:9: error: unknown channel 'forse' (did you mean 'force'?); a channel is one "
          "of time, power, duty, current, deflection, force, temperature, ambient_temperature, "
          "inductance, inductance_measure, decay_time, resistance, optionally after an "
          "instance's name (left.force)");
    CHECK(data_error("time[s],left.forse[N]\n0,1\n").find("(did you mean 'left.force'?)") !=
          std::string::npos);
  }
  SECTION("a repeated channel") {
    CHECK(data_error("time[s],force[N],force[mN]\n0,1,2\n") ==
          "run.csv:1:18: error: channel 'force' appears twice (columns 2 and 3)");
  }
  SECTION("an unknown unit, a unit of another quantity, a reciprocal unit") {
    CHECK(data_error("time[s],force[blorp]\n0,1\n") ==
          "run.csv:1:15: error: 'blorp' is not a unit; expected a force, e.g. N, mN");
    // udunits2's parser leaks the identifiers of a unit it fails to parse (tests/lsan.supp);
    // the refusal itself is as clean as any other.
    CHECK(data_error("time[s],force[m 0v]\n0,1\n") ==
          "run.csv:1:15: error: 'm 0v' is not a unit; expected a force, e.g. N, mN");
    CHECK(data_error("time[s],force[mm]\n0,1\n") ==
          "run.csv:1:15: error: unit 'mm' of channel 'force' is not a force, e.g. N, mN");
    CHECK(data_error("time[Hz],force[N]\n0,1\n") ==
          "run.csv:1:6: error: unit 'Hz' of channel 'time' is not a time, e.g. s, ms");
    CHECK(data_error("time[s],temperature[C]\n0,1\n") ==
          "run.csv:1:21: error: unit 'C' of channel 'temperature' is not a temperature, e.g. K, "
          "degC");
  }
  SECTION("a ragged row") {
    CHECK(data_error("time[s],force[N]\n0,1\n1\n") ==
          "run.csv:3:2: error: expected 2 fields separated by ',' (one per heading: time force), "
          "got 1");
    CHECK(data_error("time[s],force[N]\n0,1,2\n") ==
          "run.csv:2:5: error: expected 2 fields separated by ',' (one per heading: time force), "
          "got 3");
  }
  SECTION("NaN, Inf, an empty field, a word") {
    CHECK(data_error("time[s],force[N]\n0,1\n1,nan\n") ==
          "run.csv:3:3: error: field 2 (force [N]): expected a finite number, got 'nan'");
    CHECK(data_error("time[s],force[N]\n0,-inf\n") ==
          "run.csv:2:3: error: field 2 (force [N]): expected a finite number, got '-inf'");
    CHECK(data_error("time[s],force[N]\n0,\n") ==
          "run.csv:2:3: error: field 2 (force [N]): expected a number, got ''");
    CHECK(data_error("time[s],force[N]\n0,one\n") ==
          "run.csv:2:3: error: field 2 (force [N]): expected a number, got 'one'");
  }
  SECTION("a time that repeats or goes back") {
    CHECK(data_error("time[s],force[N]\n0,1\n0.5,1\n0.5,1\n") ==
          "run.csv:4:1: error: duplicate time: 0.5 s repeats 0.5 s on line 3");
    CHECK(data_error("time[ms],force[N]\n0,1\n500,1\n400,1\n") ==
          "run.csv:4:1: error: time goes back: 0.4 s after 0.5 s on line 3; sample times must "
          "increase strictly");
  }
  SECTION("a value outside its quantity's physical range") {
    CHECK(data_error("time[s],temperature[degC]\n0,-300\n") ==
          "run.csv:2:3: error: temperature '-300' [degC] is outside the physical range 0 to inf K");
    CHECK(data_error("time[s],duty[%]\n0,120\n") ==
          "run.csv:2:3: error: duty '120' [%] is outside the physical range 0 to 1 1");
  }
  SECTION("a file that cannot be opened") {
    CHECK_THROWS_WITH(read_measured_data("/nonexistent/run.csv", *shared_units()),
                      "/nonexistent/run.csv: error: cannot open the file for reading");
  }
  SECTION("a directory") {
    const auto directory = fresh_directory("data_directory");
    CHECK_THROWS_WITH(read_measured_data(directory.string(), *shared_units()),
                      directory.string() + ": error: it is a directory, not a data file");
  }
}

TEST_CASE("A replayed power step heats the muscle as C dT/dt = P - hA (T - T_amb) says") {
  const auto directory = fresh_directory("replay_step");
  // 1 W from t = 0, held: T - T_amb = P/hA (1 - exp(-t hA/C)) with P/hA = 20 K, tau = 10 s.
  write(directory / "bench.csv", "time[ms],power[mW]\n0,1000\n50000,1000\n100000,1000\n");
  const Scenario scenario = load_scenario(
      replay_scenario(directory,
                      "{type: data, file: bench.csv, channel: power, interpolation: hold}"),
      {}, shared_units());
  const Trace trace = simulate(scenario);
  double worst = 0.0;
  for (std::size_t i = 0; i < trace.time.size(); ++i) {
    const double expected = 20.0 * (1.0 - std::exp(-trace.time[i] / 10.0));
    worst = std::max(worst, std::abs(trace["muscle/temperature"][i] - 293.15 - expected));
  }
  CHECK(worst <= allowed(1e-8, 20.0 + 293.15));
}

TEST_CASE("Linear replay joins the samples as a piecewise-linear signal of the same points does") {
  const auto directory = fresh_directory("replay_linear");
  write(directory / "bench.csv", "time[s],power[W]\n0,0\n10,2\n30,0.5\n60,1.5\n100,1.5\n");
  const Trace replayed = simulate(
      load_scenario(replay_scenario(directory, "{type: data, file: bench.csv, channel: power}"), {},
                    shared_units()));
  const Trace written = simulate(load_scenario(
      replay_scenario(directory,
                      "{type: piecewise_linear, times: [0 s, 10 s, 30 s, 60 s, 100 s], "
                      "values: [0 W, 2 W, 0.5 W, 1.5 W, 1.5 W]}"),
      {}, shared_units()));
  CHECK(replayed.statistics.steps == written.statistics.steps);
  CHECK(max_abs_difference(replayed["muscle/temperature"], written["muscle/temperature"]) <= 1e-12);
  CHECK(max_abs_difference(replayed["drive/power"], written["drive/power"]) == 0.0);

  // The same samples recorded 10 s later, with origin 10 s: the data's 10 s is the run's 0 s.
  write(directory / "later.csv", "time[s],power[W]\n10,0\n20,2\n40,0.5\n70,1.5\n110,1.5\n");
  const Trace shifted = simulate(load_scenario(
      replay_scenario(directory, "{type: data, file: later.csv, channel: power, origin: 10 s}"), {},
      shared_units()));
  CHECK(bitwise_equal(shifted["drive/power"], replayed["drive/power"]));
  CHECK(bitwise_equal(shifted["muscle/temperature"], replayed["muscle/temperature"]));
}

TEST_CASE("A data signal finds the sample at any time, whether the rate is even or not") {
  // 16 Hz with jitter, a gap of seven missing samples, then a burst at 1 kHz: the sample the
  // mean rate points at is often not the one, and the signal must still use the last sample at
  // or before the time asked (as a search of every sample does), held or joined by lines.
  RandomStream stream(3, "irregular samples");
  auto samples = std::make_shared<DataSignal::Samples>();
  double time = 2.0;
  for (int k = 0; k < 400; ++k) {
    samples->times.push_back(time);
    samples->values.push_back(stream.uniform(-1.0, 1.0));
    time += k == 200 ? 8.0 / 16.0 : k > 300 ? 1e-3 : (1.0 + stream.uniform(-0.3, 0.3)) / 16.0;
  }
  std::vector<double> asked = {0.0, 1.999, samples->times.back() + 1.0};
  for (const double at : samples->times) {
    asked.insert(asked.end(), {at, std::nextafter(at, 0.0), std::nextafter(at, 1e9), at + 1e-4});
  }
  for (int k = 0; k < 2000; ++k) asked.push_back(stream.uniform(1.5, time + 0.5));
  const auto& t = samples->times;
  const auto& v = samples->values;
  for (const auto interpolation : {DataInterpolation::hold, DataInterpolation::linear}) {
    const DataSignal signal(samples, interpolation, 0.0);
    for (const double at : asked) {
      long last = -1;  // the last sample at or before `at`, by looking at every one
      for (std::size_t k = 0; k < t.size(); ++k)
        if (t[k] <= at) last = static_cast<long>(k);
      double expected = last < 0 ? v.front() : v[static_cast<std::size_t>(last)];
      double slope = 0.0;
      const auto k = static_cast<std::size_t>(last);
      if (interpolation == DataInterpolation::linear && last >= 0 && k + 1 < t.size()) {
        expected = v[k] + (at - t[k]) / (t[k + 1] - t[k]) * (v[k + 1] - v[k]);
        slope = (v[k + 1] - v[k]) / (t[k + 1] - t[k]);
      }
      INFO("t = " << at << ", last sample " << last);
      CHECK(signal.value(at) == expected);
      CHECK(signal.slope(at) == slope);
    }
  }
}

TEST_CASE("A data signal's file, channel and coverage are checked at the scenario's keys") {
  const auto directory = fresh_directory("replay_errors");
  write(directory / "bench.csv", "time[s],power[W],force[N]\n0,1,0.1\n50,1,0.1\n");
  const auto file = [&](const std::string& signal) { return replay_scenario(directory, signal); };
  const std::string data = (directory / "bench.csv").string();
  const std::string scenario = (directory / "replay.yaml").string();
  SECTION("a channel the file lacks") {
    CHECK(scenario_error(file("{type: data, file: bench.csv, channel: powr}")) ==
          scenario + ":14:68: error: drive.power.channel: " + data +
              " has no channel 'powr' (did you mean 'power'?); its channels: time, power, force");
  }
  SECTION("a channel of another quantity") {
    CHECK(scenario_error(file("{type: data, file: bench.csv, channel: force}")) ==
          scenario +
              ":14:68: error: drive.power.channel: channel 'force' is in N; this signal "
              "takes W");
  }
  SECTION("data that end before the scenario does, or start after its t = 0") {
    write(directory / "short.csv", "time[s],power[W]\n0,1\n40,1\n");
    CHECK(scenario_error(file("{type: data, file: short.csv, channel: power}")) ==
          scenario +
              ":14:48: error: drive.power.file: the data cover the scenario only until "
              "t = 80 s (a sample interval past the last sample); the scenario lasts 100 s");
    CHECK(scenario_error(file("{type: data, file: bench.csv, channel: power, origin: -1 s}")) ==
          scenario +
              ":14:48: error: drive.power.file: the data start at 0 s, after origin -1 s "
              "(the data time of the scenario's t = 0)");
  }
  SECTION("a data signal without a file, in a scenario without a measurement") {
    CHECK(scenario_error(file("{type: data, channel: power}")) ==
          scenario +
              ":14:29: error: drive.power: expected a file to replay: 'file', or the "
              "scenario's measurement.file (fit and discover set it to their --data; run "
              "takes --set measurement.file=FILE)");
  }
  SECTION("an error inside the data file is located there") {
    write(directory / "broken.csv", "time[s],power[W]\n0,1\n1,x\n");
    CHECK(scenario_error(file("{type: data, file: broken.csv, channel: power}")) ==
          (directory / "broken.csv").string() +
              ":3:3: error: field 2 (power [W]): expected a number, got 'x'");
  }
}

TEST_CASE("Data signals without a file of their own replay the scenario's measurement") {
  const auto directory = fresh_directory("measurement_file");
  write(directory / "bench.csv", "time[s],power[W]\n0,0\n10,2\n30,0.5\n60,1.5\n100,1.5\n");
  write(directory / "other.csv", "time[s],power[W]\n0,1\n100,1\n");
  const std::string own =
      replay_scenario(directory, "{type: data, file: bench.csv, channel: power}");
  const Trace expected = simulate(load_scenario(own, {}, shared_units()));
  const std::string shared = replay_scenario(directory, "{type: data, channel: power}");
  // measurement.file is found beside the scenario when written in it...
  write(shared, "measurement: {file: bench.csv}\n" + read_text_file(shared));
  CHECK(bitwise_equal(simulate(load_scenario(shared, {}, shared_units()))["muscle/temperature"],
                      expected["muscle/temperature"]));
  // ...and from the working directory when set on the command line.
  const Trace other = simulate(load_scenario(
      shared, {"measurement.file=" + (directory / "other.csv").string()}, shared_units()));
  CHECK(other["drive/power"].front() == 1.0);
}

TEST_CASE("A tcpmsim record stands in for a measurement: channels by path, in SI, unchanged") {
  const auto directory = fresh_directory("record_as_data");
  const std::string yaml =
      replaced(physical_muscle_yaml(), "power: 0 W",
               "power: {type: random_steps, range: [0 W, 2 W], process_time_constant: 5 s, "
               "sample_rate: 10 Hz, duration: 100 s}");
  write(directory / "source.yaml", yaml);
  const Scenario source = load_scenario((directory / "source.yaml").string(), {}, shared_units());
  const Trace trace = simulate(source);
  REQUIRE(run_scenario(source, (directory / "source.h5").string()).succeeded);

  const MeasuredData data = read_measured_data((directory / "source.h5").string(), *shared_units());
  CHECK(bitwise_equal(data.time(), trace.time));
  for (const std::string name : {"muscle.temperature", "load.force", "drive.power"}) {
    INFO(name);
    REQUIRE(data.find(name) != nullptr);
    std::string slashed = name;
    slashed[slashed.find('.')] = '/';
    CHECK(bitwise_equal(data.find(name)->values, trace[slashed]));
  }
  CHECK(data.find("muscle.temperature")->unit == "K");
  CHECK(data.find("inputs.drive.power") == nullptr);
  // As the bench measures: the drive's power, the testing machine's deflection and load cell.
  CHECK(bitwise_equal(data.find("power")->values, trace["drive/power"]));
  CHECK(bitwise_equal(data.find("deflection")->values, trace["load/deflection"]));
  CHECK(bitwise_equal(data.find("force")->values, trace["load/force"]));
  CHECK(bitwise_equal(data.find("temperature")->values, trace["muscle/temperature"]));

  // Its power replayed with a zero-order hold is the step signal through the recorded samples
  // where the power changes: the same values and breakpoints, so the same run bit for bit.
  const Trace replayed =
      simulate(load_scenario(replay_scenario(directory,
                                             "{type: data, file: source.h5, channel: drive.power, "
                                             "interpolation: hold}"),
                             {}, shared_units()));
  const auto& power = trace["drive/power"];
  std::ostringstream times, values;
  for (std::size_t k = 1; k < power.size(); ++k) {
    if (power[k] == power[k - 1]) continue;
    times << (times.tellp() > 0 ? ", " : "") << number(trace.time[k]) << " s";
    values << (values.tellp() > 0 ? ", " : "") << number(power[k]) << " W";
  }
  const std::string steps = "{type: steps, initial: " + number(power[0]) + " W, times: [" +
                            times.str() + "], values: [" + values.str() + "]}";
  const Trace stepped =
      simulate(load_scenario(replay_scenario(directory, steps), {}, shared_units()));
  CHECK(bitwise_equal(replayed["drive/power"], trace["drive/power"]));
  CHECK(bitwise_equal(replayed["muscle/temperature"], stepped["muscle/temperature"]));
  CHECK(bitwise_equal(replayed["load/force"], stepped["load/force"]));
}

TEST_CASE("An HDF5 file that is not a tcpmsim record is refused as data") {
  const auto directory = fresh_directory("not_a_record");
  const std::string path = (directory / "other.h5").string();
  H5::H5File(path, H5F_ACC_TRUNC).createGroup("/measurements");
  CHECK_THROWS_WITH(read_measured_data(path, *shared_units()),
                    path + ": error: not a tcpmsim record: it has no /time dataset");
}
