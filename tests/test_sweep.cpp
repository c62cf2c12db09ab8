// Parameter sweeps (issue 11): the design of the runs, the located errors of a sweep file, one
// model with a context per run on any number of threads, failures recorded, resumption.
#include <catch2/catch.hpp>

#include <H5Cpp.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>

#include "sim/config/config_error.h"
#include "sim/io/hdf5_files.h"
#include "sim/run.h"
#include "sweep/batch_run.h"
#include "sweep/sweep_design.h"
#include "sweep/sweep_executor.h"
#include "sweep/sweep_run.h"
#include "sweep/sweep_spec.h"
#include "sweep/sweep_store.h"
#include "sweep/sweep_table.h"
#include "tests/support/record_digest.h"
#include "tests/support/test_support.h"

using namespace tcpmsim;
using namespace tcpmsim::sweep;
using namespace tcpmsim::testing;

namespace {

// A scratch directory holding sweep files that name the repository's scenarios.
struct SweepDirectory {
  std::filesystem::path path;
  SweepDirectory() {
    path = std::filesystem::temp_directory_path() /
           ("tcpmsim_sweep_" + std::to_string(reinterpret_cast<std::uintptr_t>(this)));
    std::filesystem::create_directories(path);
  }
  ~SweepDirectory() { std::filesystem::remove_all(path); }
  std::string write(const std::string& name, const std::string& text) const {
    const auto file = (path / name).string();
    std::ofstream(file) << text;
    return file;
  }
};

const std::string kStepScenario =
    "scenario: " + source_path("configs/sweeps/thermal_step.yaml") + "\n";

std::string sweep_error(const std::string& text, const std::vector<std::string>& overrides = {}) {
  SweepDirectory directory;
  const std::string file = directory.write("sweep.yaml", text);
  try {
    load_sweep(file, overrides, shared_units());
  } catch (const ConfigError& error) {
    return error.what();
  }
  return "";
}

std::vector<double> read_column(const std::string& file, const std::string& name) {
  const H5::H5File h5(file, H5F_ACC_RDONLY);
  H5::DataSet set = h5.openDataSet("/summary/" + name);
  std::vector<double> values(static_cast<std::size_t>(set.getSpace().getSimpleExtentNpoints()));
  set.read(values.data(), H5::PredType::NATIVE_DOUBLE);
  return values;
}

std::vector<std::string> summary_texts(const std::string& file, const std::string& name) {
  return read_texts(H5::H5File(file, H5F_ACC_RDONLY), "/summary/" + name);
}

// The step scenario over hA x C: 2 x 2 runs.
const std::string kGridSweep = "sweep: {name: grid}\n" + kStepScenario + R"(
axes:
  - parameter: muscle.thermal.conductance
    values: [40 mW/K, 80 mW/K]
  - parameter: muscle.thermal.heat_capacity
    range: {from: 0.3 J/K, to: 0.6 J/K, count: 2, spacing: log}
metrics:
  - {name: time_constant, type: time_constant, channel: muscle/temperature, from: 10 s}
  - {name: peak_temperature, type: maximum, channel: muscle/temperature}
  - {name: rise_time, type: rise_time, channel: muscle/temperature, from: 10 s}
  - {name: heat, type: integral, channel: drive/power, rule: held}
)";

}  // namespace

TEST_CASE("ranges include both ends exactly and space their values linearly or by ratio",
          "[sweep]") {
  CHECK(spaced_values(1.0, 3.0, 3, Spacing::linear) == std::vector<double>{1.0, 2.0, 3.0});
  const auto log = spaced_values(0.1, 10.0, 3, Spacing::logarithmic);
  CHECK(log.front() == 0.1);
  CHECK(log.back() == 10.0);
  CHECK(log[1] == Approx(1.0).epsilon(1e-15));
  CHECK(spaced_values(2.0, 5.0, 1, Spacing::linear) == std::vector<double>{2.0});
}

TEST_CASE("a Latin hypercube column puts exactly one value in each stratum, reproducibly",
          "[sweep]") {
  RandomStream stream(7, "axis"), again(7, "axis");
  const auto values = latin_hypercube_values(0.0, 10.0, 10, Spacing::linear, stream);
  std::set<int> strata;
  for (double value : values) strata.insert(static_cast<int>(std::floor(value)));
  CHECK(strata.size() == 10);
  CHECK(latin_hypercube_values(0.0, 10.0, 10, Spacing::linear, again) == values);
  // In log space: one value per decade of [1, 1e4].
  RandomStream decades(1, "log");
  std::set<int> exponents;
  for (double value : latin_hypercube_values(1.0, 1e4, 4, Spacing::logarithmic, decades))
    exponents.insert(static_cast<int>(std::floor(std::log10(value))));
  CHECK(exponents == std::set<int>{0, 1, 2, 3});
}

TEST_CASE("a grid takes every combination, the last axis fastest; zipped axes move together",
          "[sweep]") {
  const auto runs = grid_runs({{{1, 2}}, {{10, 20, 30}, {100, 200, 300}}});
  REQUIRE(runs.size() == 6);
  CHECK(runs[0] == std::vector<double>{1, 10, 100});
  CHECK(runs[1] == std::vector<double>{1, 20, 200});
  CHECK(runs[5] == std::vector<double>{2, 30, 300});
  CHECK_THROWS_AS(grid_runs({{{1, 2}, {1, 2, 3}}}), std::invalid_argument);
  CHECK(grid_runs({}).size() == 1);  // no axis: the scenario as it is
}

TEST_CASE("a grid of more than a million runs is refused before one is made", "[sweep]") {
  // Issue 31: three axes of a thousand values each asked for 24 GB at once (std::bad_alloc).
  const AxisGroup thousand{std::vector<double>(1000, 1.0)};
  const std::vector<AxisGroup> huge{thousand, thousand, thousand};
  const std::string problem =
      "the axes make 1000 x 1000 x 1000 = 1e+09 runs, over the limit of 1e+06 runs a sweep "
      "(each is a simulation, and every run's values are held in memory); give fewer values, "
      "zip axes (combine: zip), or split the sweep";
  CHECK(grid_size_problem(huge) == problem);
  CHECK_THROWS_WITH(grid_runs(huge), problem);
  CHECK(grid_size_problem({thousand, thousand}).empty());  // a million is allowed
}

TEST_CASE("a sweep file's axes, derived parameters and metrics are read with units", "[sweep]") {
  SweepDirectory directory;
  const auto spec = load_sweep(directory.write("grid.yaml", kGridSweep), {}, shared_units());
  REQUIRE(spec.runs.size() == 4);
  CHECK(spec.axes[0].unit == "W/K");
  CHECK(spec.runs[1] == std::vector<double>{0.04, 0.6});
  CHECK(spec.runs[2][0] == 0.08);
  REQUIRE(spec.metrics.size() == 4);
  CHECK(spec.metrics[0].unit == "s");
  CHECK(spec.metrics[1].unit == "K");
  CHECK(spec.metrics[3].unit == "W*s");
}

TEST_CASE("a bad sweep file gets one located error before any run", "[sweep]") {
  const std::string head = "sweep: {name: bad}\n" + kStepScenario;
  const auto axis = [&](const std::string& text) { return head + "axes:\n  - " + text + "\n"; };
  CHECK_THAT(sweep_error(axis("{parameter: muscle.thermal.conductanse, values: [1 W/K]}")),
             Catch::Contains("sweep.yaml:4:17") &&
                 Catch::Contains("'muscle.thermal.conductanse' is not a parameter of scenario"));
  CHECK_THAT(sweep_error(axis("{parameter: muscle.thermal.conductance, values: [1 J/K]}")),
             Catch::Contains("sweep.yaml:4:") && Catch::Contains("axes[0].values[0]") &&
                 Catch::Contains("cannot be converted to 'W/K'"));
  CHECK_THAT(sweep_error(axis("{parameter: muscle.thermal.conductance, values: []}")),
             Catch::Contains("an empty list of values"));
  // Axes each within their caps whose product is not: at the axes, with the product and cap.
  CHECK_THAT(sweep_error(head + "axes:\n"
                                "  - {parameter: muscle.thermal.conductance, range: {from: 1 W/K, "
                                "to: 2 W/K, count: 1000}}\n"
                                "  - {parameter: muscle.thermal.heat_capacity, range: {from: 1 "
                                "J/K, to: 2 J/K, count: 1000}}\n"
                                "  - {parameter: muscle.mechanics.k1, range: {from: 1 N/m, to: 2 "
                                "N/m, count: 1000}}\n"),
             Catch::Contains("sweep.yaml:3:1: error: axes: the axes make 1000 x 1000 x 1000 = "
                             "1e+09 runs, over the limit of 1e+06 runs a sweep"));
  CHECK_THAT(
      sweep_error(axis("{parameter: muscle.thermal.conductance, range: {from: 1 W/K, to: 2 W/K, "
                       "count: 0}}")),
      Catch::Contains("axes[0].range.count") && Catch::Contains("a value in [1, 1e+06]"));
  CHECK_THAT(sweep_error(axis("{parameter: muscle.thermal.conductance, range: {from: 0 W/K, "
                              "to: 2 W/K, count: 3, spacing: log}}")),
             Catch::Contains("a log range needs ends of one sign"));
  CHECK_THAT(
      sweep_error(head + "combine: zip\naxes:\n"
                         "  - {parameter: muscle.thermal.conductance, values: [1 W/K, 2 W/K]}\n"
                         "  - {parameter: muscle.thermal.heat_capacity, values: [1 J/K]}\n"),
      Catch::Contains("zipped axes must have equal lengths"));
  CHECK_THAT(
      sweep_error(head + "metrics:\n  - {name: t, type: maximum, channel: muscle/temprature}\n"),
      Catch::Contains("records no output 'muscle/temprature'") &&
          Catch::Contains("did you mean 'muscle/temperature'"));
  CHECK_THAT(sweep_error(head + "derived:\n  - {parameter: muscle.thermal.conductance, "
                                "multiply: [muscle.thermal.heat_capacity]}\n"),
             Catch::Contains("the product has the unit"));
  // A misspelt parameter's range is reported at its path, not as a unit that no number takes.
  CHECK_THAT(sweep_error(axis("{parameter: muscle.thermal.conductanse, range: {from: 29 mW/K, "
                              "to: 116 mW/K, count: 3}}")),
             Catch::Contains("unknown parameter 'muscle.thermal.conductanse' (did you mean "
                             "'muscle.thermal.conductance'?"));
  CHECK_THAT(sweep_error("sweep: {name: bad}\nscenario: nowhere.yaml\n"),
             Catch::Contains("no scenario file"));
  // A structural axis' every value is tried, not only its first.
  CHECK_THAT(sweep_error(axis("{parameter: solver.rtol, values: [1e-6, -1]}")),
             Catch::Contains("axes[0].parameter") && Catch::Contains("setting it to '-1'"));
  // Summary columns are named once.
  CHECK_THAT(sweep_error(head + "metrics:\n  - {name: status, type: maximum, "
                                "channel: muscle/temperature}\n"),
             Catch::Contains("metrics[0].name") &&
                 Catch::Contains("summary column 'status' is already the run's status"));
  CHECK_THAT(sweep_error(axis("{parameter: muscle.thermal.conductance, values: [1 W/K]}") +
                         "metrics:\n  - {name: muscle.thermal.conductance, type: maximum, "
                         "channel: muscle/temperature}\n"),
             Catch::Contains("already an axis'"));
  CHECK_THAT(sweep_error(head + "metrics:\n  - {name: r, type: rise_time, "
                                "channel: muscle/temperature}\n"),
             Catch::Contains("an open-loop rise time needs 'from'"));
  CHECK_THAT(sweep_error(head + "metrics:\n  - {name: m, type: maximum, "
                                "channel: muscle/temperature, from: 500 s}\n"),
             Catch::Contains("metrics[0].from: the window starts after the scenario ends (400 s)"));
  // A `set:` entry the scenario refuses is blamed where the sweep file says it.
  CHECK_THAT(
      sweep_error(head + "set: ['solver.rtol=-1']\n"),
      Catch::Contains("sweep.yaml:3:7: error: set[0]: scenario 'scenario' does not take it"));
  // Also a key the entry adds (issue 13: the error named the file, so the whole list was blamed).
  CHECK_THAT(sweep_error(head + "set: ['nonsense.key=3']\n"),
             Catch::Contains("sweep.yaml:3:7: error: set[0]: scenario 'scenario' does not take "
                             "it: nonsense: unknown key 'nonsense'"));
}

TEST_CASE("A --set that stores full traces says how to drop a decimated store's interval",
          "[sweep]") {
  const std::string decimated =
      "sweep: {name: traces}\n" + kStepScenario + "store: {traces: decimated, interval: 10 s}\n";
  CHECK(sweep_error(decimated) == "");
  CHECK_THAT(sweep_error(decimated, {"store.traces=full"}),
             Catch::Contains("sweep.yaml:") &&
                 Catch::Contains("store.interval: applies to traces: decimated only (traces "
                                 "here: full); give the store without it, e.g. --set "
                                 "'store={traces: full}'"));
  CHECK(sweep_error(decimated, {"store={traces: full}"}) == "");
}

TEST_CASE("a structural axis builds the scenario again for each of its values", "[sweep]") {
  SweepDirectory directory;
  const std::string text =
      "sweep: {name: seeds}\n" + kStepScenario +
      "axes:\n  - {parameter: scenario.duration, values: [50 s, 60 s]}\n"
      "metrics:\n  - {name: last, type: final_value, channel: muscle/temperature}\n";
  const auto spec = load_sweep(directory.write("seeds.yaml", text), {}, shared_units());
  REQUIRE(spec.axes[0].structural);
  CHECK(spec.axes[0].texts == std::vector<std::string>{"50 s", "60 s"});
  const std::string output = (directory.path / "seeds.h5").string();
  run_sweep(spec, {output, 2, false}, shared_units());
  CHECK(summary_texts(output, "scenario.duration") == std::vector<std::string>{"50 s", "60 s"});
  const auto last = read_column(output, "last");
  CHECK(last[1] > last[0]);  // heated 10 s longer
}

TEST_CASE("a metric without 'to' ends with each run, whatever duration its structural axis gives",
          "[sweep]") {
  SweepDirectory directory;
  // The base runs 12 s; the second run 30 s, past the base's end.
  const std::string text =
      "sweep: {name: durations}\n" + kStepScenario +
      "set: [scenario.duration=12 s]\n"
      "axes:\n  - {parameter: scenario.duration, values: [12 s, 30 s]}\n"
      "metrics:\n  - {name: last, type: final_value, channel: muscle/temperature}\n";
  const auto spec = load_sweep(directory.write("durations.yaml", text), {}, shared_units());
  const std::string output = (directory.path / "durations.h5").string();
  run_sweep(spec, {output, 1, false}, shared_units());
  // 0.5 W from t = 10 s into C = 0.55 J/K, hA = 73 mW/K: T - T_amb = P/hA (1 - exp(-(t - 10
  // s)/tau)).
  const double tau = 0.55 / 0.073, rise = 0.5 / 0.073, ambient = 296.15;
  const auto last = read_column(output, "last");
  CHECK(last[0] == Approx(ambient + rise * (1.0 - std::exp(-2.0 / tau))).epsilon(1e-6));
  CHECK(last[1] == Approx(ambient + rise * (1.0 - std::exp(-20.0 / tau))).epsilon(1e-6));
}

TEST_CASE("a spread in degC is a temperature difference: 0.5 degC spreads by 0.5 K", "[sweep]") {
  SweepDirectory directory;
  const std::string text =
      "sweep: {name: spread}\n" + kStepScenario +
      "axes:\n  - {parameter: muscle.thermal.ambient_temperature, random: {distribution: normal, "
      "mean: 23 degC, standard_deviation: 0.5 degC, count: 400}}\n";
  const auto spec = load_sweep(directory.write("spread.yaml", text), {}, shared_units());
  double sum = 0.0, squares = 0.0;
  for (const auto& run : spec.runs) sum += run[0];
  const double mean = sum / static_cast<double>(spec.runs.size());
  for (const auto& run : spec.runs) squares += (run[0] - mean) * (run[0] - mean);
  const double deviation = std::sqrt(squares / static_cast<double>(spec.runs.size() - 1));
  // 400 draws: the mean within 4 standard errors (0.1 K), the deviation within 15 %.
  CHECK(mean == Approx(296.15).margin(0.1));
  CHECK(deviation == Approx(0.5).epsilon(0.15));
}

TEST_CASE(
    "a structural axis on the output rate that decimated traces cannot follow fails that "
    "run, before it integrates, and says why",
    "[sweep]") {
  SweepDirectory directory;
  const std::string text = "sweep: {name: rates}\n" + kStepScenario +
                           "set: [scenario.duration=8 s]\n"
                           "axes:\n  - {parameter: output.rate, values: [1 Hz, 0.25 Hz]}\n"
                           "store: {traces: decimated, interval: 1 s}\n";
  const auto spec = load_sweep(directory.write("rates.yaml", text), {}, shared_units());
  const std::string output = (directory.path / "rates.h5").string();
  const auto outcome = run_sweep(spec, {output, 1, false}, shared_units());
  CHECK(outcome.failed == 1);
  CHECK(summary_texts(output, "status") == std::vector<std::string>{"ok", "failed"});
  CHECK(summary_texts(output, "message")[1] ==
        "store.interval (1 s) is no multiple of this run's output interval (4 s): its traces "
        "cannot be decimated");
}

TEST_CASE("a scenario's name is one group of the output: '/', '.', '..' and '' are refused",
          "[sweep]") {
  const std::string file = source_path("configs/sweeps/thermal_step.yaml");
  for (const std::string name : {"a/b", ".", "..", ""}) {
    const std::string text = "sweep: {name: named}\nscenarios: {\"" + name + "\": " + file +
                             "}\naxes:\n  - {parameter: muscle.thermal.conductance, values: "
                             "[29 mW/K]}\n";
    CHECK_THAT(sweep_error(text),
               Catch::Contains("the scenario's name '" + name +
                               "' names its traces' group in the output: expected a name without "
                               "'/', and not '', '.' or '..'"));
  }
}

TEST_CASE("a sweep's results do not depend on the thread count, and obey C dT/dt = P - hA dT",
          "[sweep][thread]") {
  SweepDirectory directory;
  const auto spec = load_sweep(directory.write("grid.yaml", kGridSweep), {}, shared_units());
  const std::string one = (directory.path / "one.h5").string();
  const std::string two = (directory.path / "two.h5").string();
  run_sweep(spec, {one, 1, false}, shared_units());
  const auto outcome = run_sweep(spec, {two, 2, false}, shared_units());
  CHECK(outcome.failed == 0);
  for (const std::string column : {"muscle.thermal.conductance", "muscle.thermal.heat_capacity",
                                   "time_constant", "peak_temperature", "rise_time", "heat"}) {
    INFO(column);
    CHECK(bitwise_equal(read_column(one, column), read_column(two, column)));
  }
  const auto hA = read_column(two, "muscle.thermal.conductance");
  const auto C = read_column(two, "muscle.thermal.heat_capacity");
  const auto tau = read_column(two, "time_constant");
  const auto rise = read_column(two, "rise_time");
  const auto peak = read_column(two, "peak_temperature");
  const auto heat = read_column(two, "heat");
  for (std::size_t run = 0; run < tau.size(); ++run) {
    INFO("run " << run);
    CHECK(tau[run] == Approx(C[run] / hA[run]).epsilon(1e-6));
    CHECK(rise[run] == Approx(C[run] / hA[run] * std::log(9.0)).epsilon(1e-3));  // tau ln 9
    CHECK(peak[run] - 296.15 == Approx(0.5 / hA[run]).epsilon(1e-4));  // P / hA, 39 tau after
    CHECK(heat[run] == Approx(0.5 * 390.0).epsilon(1e-12));            // 0.5 W from 10 s, held
  }
}

TEST_CASE("a run that fails is recorded with its message, and the sweep goes on", "[sweep]") {
  SweepDirectory directory;
  // With traces kept: the failed run has none, and the merge copes.
  const std::string text = "sweep: {name: failing}\n" + kStepScenario +
                           "axes:\n  - {parameter: muscle.thermal.heat_capacity, values: "
                           "[0.5 J/K, -1 J/K, 0.25 J/K]}\n"
                           "metrics:\n  - {name: tau, type: time_constant, "
                           "channel: muscle/temperature, from: 10 s}\n"
                           "store: {traces: decimated, interval: 10 s}\n";
  const auto spec = load_sweep(directory.write("failing.yaml", text), {}, shared_units());
  const std::string output = (directory.path / "failing.h5").string();
  const auto outcome = run_sweep(spec, {output, 2, false}, shared_units());
  CHECK(outcome.failed == 1);
  CHECK(summary_texts(output, "status") == std::vector<std::string>{"ok", "failed", "ok"});
  // The table the command prints at the end: a header with units, a row per run.
  const std::string table = sweep_table(spec, output);
  CHECK_THAT(table, Catch::StartsWith("run  muscle.thermal.heat_capacity [J/K]  tau [s]"));
  CHECK_THAT(table, Catch::Contains("\n1    -1 ") && Catch::Contains("nan      failed"));
  CHECK(std::count(table.begin(), table.end(), '\n') == 4);
  const auto messages = summary_texts(output, "message");
  CHECK_THAT(messages[1], Catch::Contains("muscle.thermal.heat_capacity"));
  const auto tau = read_column(output, "tau");
  CHECK(std::isnan(tau[1]));
  CHECK(tau[2] == Approx(0.25 / 0.073).epsilon(1e-6));
  // The runs that succeeded keep their traces; the failed one has none.
  const H5::H5File file(output, H5F_ACC_RDONLY);
  CHECK(file.nameExists("/runs/0"));
  CHECK_FALSE(file.nameExists("/runs/1"));
  CHECK(file.nameExists("/runs/2"));
}

TEST_CASE("a resumed sweep redoes only the missing runs and refuses another sweep's parts",
          "[sweep]") {
  SweepDirectory directory;
  const std::string file = directory.write("grid.yaml", kGridSweep);
  const auto spec = load_sweep(file, {}, shared_units());
  const std::string whole = (directory.path / "whole.h5").string();
  const std::string resumed = (directory.path / "resumed.h5").string();
  run_sweep(spec, {whole, 1, false}, shared_units());
  {  // an interrupted sweep: two of four runs stored
    const SweepStore store(spec, resumed, SweepStore::Access::create);
    ScenarioLoader loader(shared_units());
    store.write(execute_run(spec, 0, loader));
    store.write(execute_run(spec, 3, loader));
    CHECK(store.pending() == std::vector<std::size_t>{1, 2});
  }
  CHECK_THROWS_WITH(run_sweep(spec, {resumed, 2, false}, shared_units()),
                    Catch::Contains("--resume"));
  const auto changed = load_sweep(file, {"axes[0].values[0]=41 mW/K"}, shared_units());
  CHECK_THROWS_WITH(run_sweep(changed, {resumed, 2, true}, shared_units()),
                    Catch::Contains("runs of another sweep"));
  const auto outcome = run_sweep(spec, {resumed, 2, true}, shared_units());
  CHECK(outcome.resumed == 2);
  CHECK(!std::filesystem::exists(resumed + ".parts"));
  for (const std::string column : {"time_constant", "peak_temperature", "heat"})
    CHECK(bitwise_equal(read_column(whole, column), read_column(resumed, column)));
}

TEST_CASE(
    "a stored run that is not what the sweep writes is refused by name, and no output "
    "is left",
    "[sweep]") {
  SweepDirectory directory;
  const auto spec = load_sweep(directory.write("grid.yaml", kGridSweep), {}, shared_units());
  const std::string output = (directory.path / "edited.h5").string();
  {
    const SweepStore store(spec, output, SweepStore::Access::create);
    ScenarioLoader loader(shared_units());
    store.write(execute_run(spec, 0, loader));
  }
  const std::string part = output + ".parts/run_0.h5";
  REQUIRE(std::filesystem::exists(part));
  {  // its values emptied, as an edit (or damage) might leave them
    H5::H5File file(part, H5F_ACC_RDWR);
    file.unlink("/values");
    const hsize_t none = 0;
    file.createDataSet("/values", H5::PredType::NATIVE_DOUBLE, H5::DataSpace(1, &none));
  }
  CHECK_THROWS_WITH(run_sweep(spec, {output, 1, true}, shared_units()),
                    part + ": error: it holds 0 values and " + std::to_string(spec.metrics.size()) +
                        " metrics where the sweep has 2 and " +
                        std::to_string(spec.metrics.size()) +
                        ": not a run of this sweep as it writes them (damaged?); remove it and "
                        "--resume to run it again");
  CHECK(!std::filesystem::exists(output));
  CHECK(!std::filesystem::exists(output + ".partial"));
}

TEST_CASE("no sweep starts into the parts of one that still writes them", "[sweep]") {
  SweepDirectory directory;
  const auto spec = load_sweep(directory.write("grid.yaml", kGridSweep), {}, shared_units());
  const std::string output = (directory.path / "live.h5").string();
  const std::string parts = output + ".parts";
  {
    // A live sweep: the store that created the parts is open, and a rank has joined it.
    const SweepStore live(spec, output, SweepStore::Access::create);
    const SweepStore rank(spec, output, SweepStore::Access::join);
    CHECK(rank.writing());
    ScenarioLoader loader(shared_units());
    live.write(execute_run(spec, 0, loader));
    // A resume beside it would redo its runs and collide with its writes; a new start would
    // call its parts an interrupted sweep's.
    CHECK_THROWS_WITH(SweepStore(spec, output, SweepStore::Access::resume),
                      Catch::Contains("another sweep is writing into " + parts + " now"));
    CHECK_THROWS_WITH(run_sweep(spec, {output, 1, true}, shared_units()),
                      Catch::Contains("another sweep is writing into"));
    CHECK_THROWS_WITH(SweepStore(spec, output, SweepStore::Access::create),
                      Catch::Contains("another sweep is writing into"));
    CHECK(live.pending() == std::vector<std::size_t>{1, 2, 3});
  }
  {
    // The ranks of a launcher killed before them: the store that opened the parts is gone, a
    // writer still holds its lock.
    const FileLock orphan(parts + "/writers.lock", FileLock::Mode::shared);
    REQUIRE(orphan.taken());
    CHECK_THROWS_WITH(run_sweep(spec, {output, 1, true}, shared_units()),
                      Catch::Contains("processes of an earlier sweep still write into " + parts));
  }
  // Once every process of the first sweep has ended, the resume finishes it.
  const auto outcome = run_sweep(spec, {output, 1, true}, shared_units());
  CHECK(outcome.resumed == 1);
  CHECK(outcome.failed == 0);
  CHECK_FALSE(std::filesystem::exists(parts));
}

TEST_CASE("a batch of scenario files on two threads writes the records each would alone",
          "[sweep][thread]") {
  SweepDirectory directory;
  const std::vector<std::string> configs{source_path("configs/ch7_control/force_steps.yaml"),
                                         source_path("configs/sweeps/thermal_step.yaml"),
                                         source_path("configs/composition/two_muscles.yaml")};
  const std::string batch = (directory.path / "batch").string();
  const auto runs = run_batch({configs, {"scenario.duration=60 s"}, batch, 2}, shared_units());
  REQUIRE(runs.size() == 3);
  for (std::size_t k = 0; k < configs.size(); ++k) {
    INFO(configs[k]);
    REQUIRE(runs[k].outcome.succeeded);
    Scenario scenario = load_scenario(configs[k], {"scenario.duration=60 s"}, shared_units());
    const std::string alone = (directory.path / ("alone_" + std::to_string(k) + ".h5")).string();
    REQUIRE(run_scenario(scenario, alone).succeeded);
    CHECK(runs[k].outcome.output_path == batch + "/" + scenario.settings.name + ".h5");
    CHECK(record_digest(runs[k].outcome.output_path) == record_digest(alone));
  }
  // Two files of one scenario would write one record: refused before any run.
  CHECK_THROWS_WITH(run_batch({{configs[0], configs[0]}, {}, batch, 2}, shared_units()),
                    Catch::Contains("their records would both be"));
}

TEST_CASE("a time constant is measured on a cooling response as on a heating one", "[sweep]") {
  SweepDirectory directory;
  // 0.5 W from the start; off at 200 s: the muscle cools back with tau = C / hA.
  const std::string text =
      "sweep: {name: cooling}\n" + kStepScenario +
      "set: ['drive.power={type: steps, initial: 0.5 W, times: [200 s], values: [0 W]}']\n"
      "axes:\n  - {parameter: muscle.thermal.heat_capacity, values: [0.3 J/K, 0.6 J/K]}\n"
      "metrics:\n  - {name: tau, type: time_constant, channel: muscle/temperature, "
      "from: 200 s}\n  - {name: undershoot, type: overshoot, channel: muscle/temperature, "
      "from: 200 s}\n";
  const auto spec = load_sweep(directory.write("cooling.yaml", text), {}, shared_units());
  const std::string output = (directory.path / "cooling.h5").string();
  run_sweep(spec, {output, 2, false}, shared_units());
  const auto tau = read_column(output, "tau");
  CHECK(tau[0] == Approx(0.3 / 0.073).epsilon(1e-6));
  CHECK(tau[1] == Approx(0.6 / 0.073).epsilon(1e-6));
  // A first-order cooling never passes its final value: zero, to the solver's error on the
  // temperature relative to the step (rtol 1e-10 x 370 K / 6.8 K = 5e-9).
  for (double value : read_column(output, "undershoot")) CHECK(value == Approx(0.0).margin(2e-8));
}
