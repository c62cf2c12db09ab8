// libFuzzer target: the measured-data CSV reader (fit, discover, replayed signals).
#include <cstddef>
#include <cstdint>

#include "fuzz/fuzz_support.h"
#include "sim/config/units.h"
#include "sim/io/measured_data.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const tcpmsim::UnitSystem units;
  tcpmsim::fuzz::expect_clean_outcome(
      [&] { tcpmsim::parse_measured_csv(tcpmsim::fuzz::text_of(data, size), "fuzz.csv", units); });
  return 0;
}
