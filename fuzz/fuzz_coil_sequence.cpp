// libFuzzer target: the coil-spring sequence reader (coil-fit's measured data, thesis ch. 2-3).
#include <cstddef>
#include <cstdint>

#include "analysis/coil_sequence.h"
#include "fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  tcpmsim::fuzz::expect_clean_outcome([&] {
    tcpmsim::analysis::parse_coil_sequence(tcpmsim::fuzz::text_of(data, size), "S9_01.csv",
                                           "S9_01");
  });
  return 0;
}
