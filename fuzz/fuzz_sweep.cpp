// libFuzzer target: a sweep file (tcpmsim sweep FILE, as far as its first run: the file, the
// scenarios it names, its axes, design, derived parameters and metrics, and the sizes they make).
// The input is the sweep file, written beside links to configs/sweeps/, so that the scenarios it
// names (thermal_step.yaml, ...) resolve as they do in the repository.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

#include "fuzz/fuzz_support.h"
#include "sim/config/units.h"
#include "sweep/sweep_spec.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const auto units = std::make_shared<const tcpmsim::UnitSystem>();
  static const std::string directory = tcpmsim::fuzz::scratch_directory("sweep", "configs/sweeps");
  const std::string file = directory + "/fuzz_sweep.yaml";
  tcpmsim::fuzz::write_file(file, tcpmsim::fuzz::text_of(data, size));
  tcpmsim::fuzz::expect_clean_outcome([&] { tcpmsim::sweep::load_sweep(file, {}, units); });
  return 0;
}
