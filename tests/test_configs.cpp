// Every scenario shipped in configs/ loads and runs to completion.
#include <yaml-cpp/yaml.h>
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "identification/bench_measurement.h"
#include "identification/fit_spec.h"
#include "sim/run.h"
#include "sweep/sweep_spec.h"
#include "tests/support/test_support.h"

using namespace tcpmsim;
using namespace tcpmsim::testing;

namespace {

// A sweep file (configs/sweeps/*.yaml with a `sweep:` section) names scenarios rather than being
// one.
bool is_sweep_file(const std::filesystem::path& path) {
  return YAML::LoadFile(path.string())["sweep"].IsDefined();
}

// A fit file (configs/discover/*_fit.yaml) names a model and a measurement.
bool is_fit_file(const std::filesystem::path& path) {
  return YAML::LoadFile(path.string())["model"].IsDefined();
}

// A bench file (configs/discover/*_bench.yaml) lists instruments, for `tcpmsim measure`.
bool is_bench_file(const std::filesystem::path& path) {
  return YAML::LoadFile(path.string())["channels"].IsDefined();
}

// Every scenario file runs with a measurement at hand: those that replay none ignore it.
std::vector<std::string> with_measurement() {
  return {"measurement.file=" + protocol_record()};
}

// The scenario files of configs/: not the spring geometries, the sweep or the fit files.
std::vector<std::filesystem::path> scenario_files() {
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(source_path("configs"))) {
    if (entry.path().extension() != ".yaml") continue;
    if (entry.path().parent_path().filename() == "springs") continue;  // geometry files
    if (is_sweep_file(entry.path()) || is_fit_file(entry.path()) || is_bench_file(entry.path()))
      continue;
    files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace

TEST_CASE("Every file in configs/ runs to the end and samples at its output rate") {
  int count = 0;
  for (const auto& file : scenario_files()) {
    ++count;
    INFO(file.filename().string());
    Scenario scenario = load_scenario(file.string(), with_measurement(), shared_units());
    // The thesis' muscles and springs lie inside every typical range: no shipped file warns.
    CHECK(scenario.warnings.empty());
    const Trace trace = simulate(scenario);
    const auto expected = static_cast<std::size_t>(std::floor(
                              (scenario.settings.duration - scenario.settings.output_start) /
                                  scenario.settings.output_interval +
                              1e-9)) +
                          1;
    // The end is recorded as well when it is not on the grid.
    const double last_on_grid =
        scenario.settings.output_start + double(expected - 1) * scenario.settings.output_interval;
    const bool end_on_grid =
        std::abs(last_on_grid - scenario.settings.duration) <= 1e-9 * scenario.settings.duration;
    CHECK(trace.time.size() == expected + (end_on_grid ? 0 : 1));
    CHECK(trace.time.back() == scenario.settings.duration);
    // Estimates are NaN (unknown) until their first measurement, then always finite; nothing is
    // ever infinite.
    for (const auto& [name, values] : trace.channels) {
      INFO(name);
      const auto first_known =
          std::find_if(values.begin(), values.end(), [](double v) { return !std::isnan(v); });
      CHECK(std::all_of(first_known, values.end(), [](double v) { return std::isfinite(v); }));
      CHECK(first_known - values.begin() < 10);
    }
  }
  CHECK(count >= 2);
}

TEST_CASE("In every scenario each component writes exactly its own outputs and derivatives") {
  for (const auto& file : scenario_files()) {
    INFO(file.filename().string());
    Scenario scenario = load_scenario(file.string(), with_measurement(), shared_units());
    Context context = scenario.make_context();
    double* state = context.state().data();
    scenario.system->initialize(context, 0.0, state);
    scenario.system->at_breakpoint(context, 0.0, 0.0, state);
    CHECK(scenario.system->check_component_contracts(context, 0.0, state) == "");
  }
}

TEST_CASE("Every fit file in configs/ loads its model, outputs and parameters") {
  int count = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(source_path("configs"))) {
    if (entry.path().extension() != ".yaml" || !is_fit_file(entry.path())) continue;
    INFO(entry.path().filename().string());
    const auto spec =
        fit::load_fit(entry.path().string(), {}, protocol_record(), 1, shared_units());
    CHECK(!spec.problem.outputs.empty());
    CHECK(!spec.problem.parameters.empty());
    ++count;
  }
  CHECK(count >= 1);
}

TEST_CASE("Every bench file in configs/ reads the chapter-7 base model") {
  const Scenario model = load_scenario(source_path("configs/discover/ch7_base.yaml"),
                                       with_measurement(), shared_units());
  int count = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(source_path("configs"))) {
    if (entry.path().extension() != ".yaml" || !is_bench_file(entry.path())) continue;
    INFO(entry.path().filename().string());
    CHECK(!fit::load_bench(entry.path().string(), model, shared_units()).instruments.empty());
    ++count;
  }
  CHECK(count >= 1);
}

TEST_CASE("Every sweep file in configs/ loads with its scenarios, axes and metrics") {
  int count = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(source_path("configs"))) {
    if (entry.path().extension() != ".yaml" || !is_sweep_file(entry.path())) continue;
    INFO(entry.path().filename().string());
    const auto spec = sweep::load_sweep(entry.path().string(), {}, shared_units());
    CHECK(!spec.runs.empty());
    CHECK(!spec.metrics.empty());
    ++count;
  }
  CHECK(count >= 1);
}
