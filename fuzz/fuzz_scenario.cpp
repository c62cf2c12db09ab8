// libFuzzer target: the scenario loader (YAML, units, kinds, the system's assembly), with the
// command line's --set. An input whose first line is "#set KEY.PATH=VALUE" gets that override
// (several such lines, several overrides); the rest is the scenario file.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "fuzz/fuzz_support.h"
#include "kinds/standard_kinds.h"
#include "sim/config/units.h"
#include "sim/scenario.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const auto units = std::make_shared<const tcpmsim::UnitSystem>();
  static const tcpmsim::KindRegistry kinds = tcpmsim::standard_kinds();
  const std::string input = tcpmsim::fuzz::text_of(data, size);
  std::vector<std::string> overrides;
  std::size_t start = 0;
  while (input.compare(start, 5, "#set ") == 0) {
    const std::size_t end = input.find('\n', start);
    overrides.push_back(input.substr(start + 5, end == std::string::npos ? end : end - start - 5));
    if (end == std::string::npos) return 0;
    start = end + 1;
  }
  tcpmsim::fuzz::expect_clean_outcome([&] {
    tcpmsim::load_scenario_text(input.substr(start), "fuzz.yaml", overrides, units, kinds);
  });
  return 0;
}
