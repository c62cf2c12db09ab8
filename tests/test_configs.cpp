// Every scenario shipped in configs/ loads and runs to completion.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>

#include "tests/support/test_support.h"

using namespace tcpmsim;
using namespace tcpmsim::testing;

TEST_CASE("Every file in configs/ runs to the end and samples at its output rate") {
  int count = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(source_path("configs"))) {
    if (entry.path().extension() != ".yaml") continue;
    if (entry.path().parent_path().filename() == "springs")
      continue;  // geometry files, not scenarios
    ++count;
    INFO(entry.path().filename().string());
    Scenario scenario = load_scenario(entry.path().string(), {}, shared_units());
    const Trace trace = simulate(scenario);
    const auto expected = static_cast<std::size_t>(std::floor(
                              (scenario.settings.duration - scenario.settings.output_start) /
                                  scenario.settings.output_interval +
                              1e-9)) +
                          1;
    CHECK(trace.time.size() >= expected);
    CHECK(trace.time.back() == scenario.settings.duration);
    for (const auto& [name, values] : trace.channels) {
      INFO(name);
      CHECK(std::all_of(values.begin(), values.end(), [](double v) { return std::isfinite(v); }));
    }
  }
  CHECK(count >= 2);
}
