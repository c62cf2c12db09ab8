// The HDF5 record: layout, units, metadata, incremental writing and atomic completion.
#include <catch2/catch.hpp>

#include <cmath>

#include <H5Cpp.h>

#include <cstdint>
#include <filesystem>
#include <fstream>

#include "sim/io/hdf5_files.h"
#include "sim/io/hdf5_recorder.h"
#include "sim/run.h"
#include "tcpmsim/version.h"
#include "tests/support/test_support.h"

using namespace tcpmsim;
using namespace tcpmsim::testing;

namespace {

std::string temporary_path(const std::string& name) {
  const auto directory = std::filesystem::temp_directory_path() / "tcpmsim_tests";
  std::filesystem::create_directories(directory);
  return (directory / name).string();
}

std::string text_attribute(const H5::H5Object& object, const std::string& name) {
  const H5::Attribute attribute = object.openAttribute(name);
  std::string value;
  attribute.read(attribute.getStrType(), value);
  return value;
}

std::vector<double> read_series(const H5::H5File& file, const std::string& path) {
  const H5::DataSet dataset = file.openDataSet(path);
  hsize_t size = 0;
  dataset.getSpace().getSimpleExtentDims(&size);
  std::vector<double> values(size);
  dataset.read(values.data(), H5::PredType::NATIVE_DOUBLE);
  return values;
}

template <typename T>
T scalar_attribute(const H5::H5Object& object, const std::string& name, const H5::PredType& type) {
  T value{};
  object.openAttribute(name).read(type, &value);
  return value;
}

}  // namespace

TEST_CASE(
    "The HDF5 record holds /time and one dataset per channel with units, identical to the run") {
  const std::string config = source_path("configs/ch7_identification.yaml");
  Scenario in_memory = load_scenario(config, {}, shared_units());
  const Trace expected = simulate(in_memory);

  Scenario scenario = load_scenario(config, {}, shared_units());
  const std::string path = temporary_path("layout.h5");
  const RunOutcome outcome = run_scenario(scenario, path);
  REQUIRE(outcome.succeeded);
  CHECK_FALSE(std::filesystem::exists(partial_path(path)));

  const H5::H5File file(path, H5F_ACC_RDONLY);
  CHECK(read_series(file, "/time") == expected.time);
  CHECK(text_attribute(file.openDataSet("/time"), "units") == "s");
  for (const auto& channel : scenario.system->channels()) {
    if (!channel.recorded) continue;  // a port, not a record
    const std::string name = channel.group + "/" + channel.name;
    INFO(name);
    const H5::DataSet dataset = file.openDataSet("/" + name);
    CHECK(text_attribute(dataset, "units") == channel.unit);
    CHECK(read_series(file, "/" + name) == expected[name]);  // bit for bit
    // Chunked (written chunk by chunk), uncompressed unless the scenario asks.
    const H5::DSetCreatPropList properties = dataset.getCreatePlist();
    CHECK(properties.getLayout() == H5D_CHUNKED);
    CHECK(properties.getNfilters() == 0);
  }
  CHECK(text_attribute(file.openDataSet("/muscle/force"), "units") == "N");
  CHECK(text_attribute(file.openDataSet("/load/deflection"), "units") == "m");

  const H5::Group root = file.openGroup("/");
  CHECK(text_attribute(root, "tcpmsim_version") == kVersion);
  CHECK(text_attribute(root, "git_commit") == kGitCommit);
  CHECK(text_attribute(root, "status") == "complete");
  CHECK(text_attribute(root, "scenario") == "ch7_identification");
  CHECK(scalar_attribute<std::uint64_t>(root, "seed", H5::PredType::NATIVE_UINT64) == 2019);
  CHECK(scalar_attribute<std::int64_t>(root, "solver_steps", H5::PredType::NATIVE_INT64) ==
        outcome.statistics.steps);
  CHECK(
      scalar_attribute<std::int64_t>(root, "solver_rhs_evaluations", H5::PredType::NATIVE_INT64) ==
      outcome.statistics.rhs_evaluations);
  // The resolved configuration is a loadable scenario that reproduces the run.
  const std::string resolved = text_attribute(root, "config");
  Scenario again = scenario_from_text(resolved);
  CHECK(simulate(again)["muscle/force"] == expected["muscle/force"]);
  // The applied signals are described for offline reconstruction.
  CHECK(text_attribute(file.openGroup("/inputs/drive.power"), "type") == "sequence");
  CHECK(text_attribute(file.openGroup("/inputs/drive.power/segment0"), "type") == "multisine");
  CHECK(text_attribute(file.openGroup("/inputs/load.deflection/segment1"), "type") ==
        "random_steps");
}

TEST_CASE("Records longer than a chunk are written chunk by chunk without loss") {
  Scenario scenario = scenario_from_text(physical_muscle_yaml(), {"drive.power=1 W"});
  const std::string path = temporary_path("chunks.h5");
  {
    Context context = scenario.make_context();
    scenario.system->prepare(context);
    // 1001 samples in chunks of 7
    Hdf5Recorder recorder(path, *scenario.system, context, {}, 7);
    Integrator integrator(*scenario.system, context, scenario.solver);
    recorder.finish(integrator.run(0.0, 100.0, 0.1, recorder));
  }
  const Trace expected = simulate(scenario);
  const H5::H5File file(path, H5F_ACC_RDONLY);
  CHECK(read_series(file, "/muscle/temperature") == expected["muscle/temperature"]);
}

TEST_CASE("Compression is a choice of output: deflate changes the file's size, never its numbers") {
  const std::string config = source_path("configs/ch7_identification.yaml");
  const std::vector<std::string> longer{"scenario.duration=200 s", "output.rate=100 Hz"};
  const auto record = [&](const std::vector<std::string>& extra, const std::string& name) {
    auto overrides = longer;
    overrides.insert(overrides.end(), extra.begin(), extra.end());
    Scenario scenario = load_scenario(config, overrides, shared_units());
    const std::string path = temporary_path(name);
    REQUIRE(run_scenario(scenario, path).succeeded);
    return path;
  };
  const std::string plain = record({}, "plain.h5");
  const std::string deflated = record({"output.compression=deflate"}, "deflated.h5");
  const std::string harder =
      record({"output.compression=deflate", "output.compression_level=9"}, "harder.h5");
  const H5::H5File plain_file(plain, H5F_ACC_RDONLY), deflated_file(deflated, H5F_ACC_RDONLY);
  for (const std::string dataset : {"/time", "/muscle/force", "/muscle/inductance_measure"})
    CHECK(bitwise_equal(read_series(plain_file, dataset), read_series(deflated_file, dataset)));
  CHECK(plain_file.openDataSet("/muscle/force").getCreatePlist().getNfilters() == 0);
  CHECK(deflated_file.openDataSet("/muscle/force").getCreatePlist().getNfilters() == 2);
  CHECK(std::filesystem::file_size(deflated) * 3 < std::filesystem::file_size(plain) * 2);
  CHECK(std::filesystem::file_size(harder) <= std::filesystem::file_size(deflated));
  // The default is not written into the resolved scenario: records made before the key keep
  // their configuration attribute.
  CHECK(text_attribute(plain_file.openGroup("/"), "config").find("compression") ==
        std::string::npos);
  CHECK_THAT(config_error(physical_muscle_yaml(), {"output.compression_level=3"}),
             Catch::Contains("output.compression_level") &&
                 Catch::Contains("give it with 'compression: deflate'"));
  CHECK_THAT(config_error(physical_muscle_yaml(), {"output.compression=zip"}),
             Catch::Contains("output.compression") && Catch::Contains("none, deflate"));
}

TEST_CASE("A failed run is kept as .failed.h5 with its reason, and never under the final name") {
  Scenario scenario =
      scenario_from_text(physical_muscle_yaml(), {"solver.max_steps=5", "drive.power=1 W"});
  const std::string path = temporary_path("failing.h5");
  std::filesystem::remove(path);
  const RunOutcome outcome = run_scenario(scenario, path);
  CHECK_FALSE(outcome.succeeded);
  CHECK_FALSE(std::filesystem::exists(path));
  CHECK_FALSE(std::filesystem::exists(partial_path(path)));
  REQUIRE(outcome.output_path == temporary_path("failing.failed.h5"));
  const H5::H5File file(outcome.output_path, H5F_ACC_RDONLY);
  const H5::Group root = file.openGroup("/");
  CHECK(text_attribute(root, "status") == "failed");
  CHECK_THAT(text_attribute(root, "failure"), Catch::Contains("more than 5 solver steps"));
}

TEST_CASE("An interrupted recording leaves no file behind") {
  Scenario scenario = scenario_from_text(physical_muscle_yaml());
  const std::string path = temporary_path("interrupted.h5");
  {
    Context context = scenario.make_context();
    Hdf5Recorder recorder(path, *scenario.system, context, {});
    CHECK(std::filesystem::exists(partial_path(path)));
  }  // destroyed without finish(): as when an exception unwinds
  CHECK_FALSE(std::filesystem::exists(partial_path(path)));
  CHECK_FALSE(std::filesystem::exists(path));
}

TEST_CASE(
    "A run stopped on request keeps as .interrupted.h5 exactly the samples an uninterrupted run "
    "has up to the time reached (issue 13)") {
  Scenario scenario = scenario_from_text(physical_muscle_yaml(), {"drive.power=0.2 W"});
  const Trace whole = simulate(scenario);
  const std::string path = temporary_path("stopped.h5");
  std::filesystem::remove(path);
  std::filesystem::remove(temporary_path("stopped.interrupted.h5"));
  const auto stop_after_40_s = [](double time, long) {
    if (time > 40.0) throw StopRequest("interrupted by a test");
  };
  const RunOutcome outcome = run_scenario(scenario, path, stop_after_40_s);
  CHECK_FALSE(outcome.succeeded);
  REQUIRE(outcome.interrupted);
  CHECK(outcome.failure == "interrupted by a test");
  CHECK(outcome.time_reached > 40.0);
  CHECK_FALSE(std::filesystem::exists(path));
  CHECK_FALSE(std::filesystem::exists(partial_path(path)));
  REQUIRE(outcome.output_path == temporary_path("stopped.interrupted.h5"));

  const H5::H5File file(outcome.output_path, H5F_ACC_RDONLY);
  const H5::Group root = file.openGroup("/");
  CHECK(text_attribute(root, "status") == "interrupted");
  CHECK(text_attribute(root, "interruption") == "interrupted by a test");
  CHECK(scalar_attribute<double>(root, "time_reached", H5::PredType::NATIVE_DOUBLE) ==
        outcome.time_reached);
  const std::vector<double> time = read_series(file, "/time");
  REQUIRE_FALSE(time.empty());
  CHECK(time.back() <= outcome.time_reached);
  CHECK(time.back() > outcome.time_reached - 0.1);  // every output time the steps covered (10 Hz)
  CHECK(scalar_attribute<std::int64_t>(root, "samples", H5::PredType::NATIVE_INT64) ==
        static_cast<std::int64_t>(time.size()));
  const auto prefix = [&](const std::vector<double>& values) {
    return std::vector<double>(values.begin(),
                               values.begin() + static_cast<std::ptrdiff_t>(time.size()));
  };
  CHECK(bitwise_equal(time, prefix(whole.time)));
  CHECK(bitwise_equal(read_series(file, "/muscle/force"), prefix(whole["muscle/force"])));
  CHECK(
      bitwise_equal(read_series(file, "/muscle/temperature"), prefix(whole["muscle/temperature"])));
}

TEST_CASE("An output path that cannot be a record is refused before anything is simulated") {
  Scenario scenario = scenario_from_text(physical_muscle_yaml());
  long steps = 0;
  const auto count_steps = [&](double, long) { ++steps; };

  SECTION("a directory") {
    const std::string directory = temporary_path("a_directory.h5");
    std::filesystem::create_directories(directory);
    CHECK_THROWS_WITH(run_scenario(scenario, directory, count_steps),
                      Catch::Contains(directory) && Catch::Contains("it is a directory"));
    CHECK_FALSE(std::filesystem::exists(partial_path(directory)));
  }
  SECTION("a device") {
    CHECK_THROWS_WITH(run_scenario(scenario, "/dev/null", count_steps),
                      Catch::Contains("/dev/null") && Catch::Contains("not a regular file"));
  }
  SECTION("a directory that cannot be made") {
    const std::string blocked = temporary_path("a_file_in_the_way");
    std::ofstream(blocked) << "x";
    const std::string path = blocked + "/record.h5";
    CHECK_THROWS_WITH(run_scenario(scenario, path, count_steps), Catch::Contains(path));
  }
  CHECK(steps == 0);
}

TEST_CASE(
    "A record's size is known before the run, and one past the limit is refused at "
    "output.rate") {
  // physical_muscle_yaml: 100 s at 10 Hz, output.rate on line 3.
  const Scenario scenario = scenario_from_text(physical_muscle_yaml());
  const RecordSize size = estimate_record_size(scenario);
  const Trace trace = simulate(scenario);
  // Exactly the samples the run records: 0, 0.1, ..., 100 s is 1001.
  CHECK(size.samples == 1001.0);
  CHECK(size.samples == static_cast<double>(trace.time.size()));
  CHECK(size.columns == static_cast<double>(trace.channels.size()) + 1.0);
  // An end off the output grid is recorded as a last sample of its own: 0, 0.3, ..., 99.9, 100.
  const Scenario off_grid = scenario_from_text(physical_muscle_yaml(), {"output.rate=3.3333 Hz"});
  CHECK(estimate_record_size(off_grid).samples ==
        static_cast<double>(simulate(off_grid).time.size()));
  CHECK_NOTHROW(check_record_size(scenario, size.bytes()));
  CHECK_THROWS_WITH(check_record_size(scenario, size.bytes() / 2),
                    Catch::StartsWith("test.yaml:3:") && Catch::Contains("output.rate") &&
                        Catch::Contains(byte_text(size.bytes())) &&
                        Catch::Contains("--max-output-size"));
  const Scenario from_set = scenario_from_text(physical_muscle_yaml(), {"output.rate=1 MHz"});
  CHECK_THROWS_WITH(check_record_size(from_set, 2e9),
                    Catch::Contains("--set output.rate=1 MHz") && Catch::Contains("2 GB"));
}

TEST_CASE("An attached effect is recorded inside its muscle's group, named instances by name") {
  Scenario scenario = scenario_from_text(
      replaced(physical_muscle_yaml(), "  resistance: 10 ohm\n",
               "  resistance: 10 ohm\n  effects: [{type: maxwell_branch, name: slow, stiffness: 5 "
               "N/m, damping: 50 N*s/m}]\n"),
      {"scenario.duration=5 s",
       "load.deflection={type: steps, initial: 20 mm, times: [1 s], "
       "values: [25 mm]}"});
  const std::string path = temporary_path("effect.h5");
  REQUIRE(run_scenario(scenario, path).succeeded);
  const Trace expected = simulate(scenario);
  const H5::H5File file(path, H5F_ACC_RDONLY);
  CHECK(text_attribute(file.openDataSet("/muscle/slow/force"), "units") == "N");
  CHECK(read_series(file, "/muscle/slow/force") == expected["muscle/slow/force"]);
  // Still relaxing 4 s after the 5 mm step: k_b dx exp(-4 s / (c_b / k_b)), tau = 10 s.
  CHECK(expected["muscle/slow/force"].back() == Approx(5.0 * 0.005 * std::exp(-0.4)).epsilon(1e-4));
  CHECK_THROWS(file.openDataSet("/muscle/slow/stiffness"));  // a port, not recorded
}
