// libFuzzer target: a fit file with its measurement (tcpmsim fit FIT --data DATA, as far as the
// fit's start: the fit file, its model, the data, the windows against the data). An input is the
// fit file, then a line "#data", then the measurement's CSV; without that line the data file
// is empty. The fit file is written beside links to configs/discover/, so that its
// `model: ch7_base.yaml` resolves as it does in the repository.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

#include "fuzz/fuzz_support.h"
#include "identification/fit_spec.h"
#include "sim/config/units.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const auto units = std::make_shared<const tcpmsim::UnitSystem>();
  static const std::string directory = tcpmsim::fuzz::scratch_directory("fit", "configs/discover");
  const std::string input = tcpmsim::fuzz::text_of(data, size);
  const std::size_t split = input.find("\n#data\n");
  const std::string fit_file = directory + "/fuzz_fit.yaml";
  const std::string data_file = directory + "/fuzz_data.csv";
  tcpmsim::fuzz::write_file(fit_file, input.substr(0, split));
  tcpmsim::fuzz::write_file(data_file,
                            split == std::string::npos ? std::string() : input.substr(split + 7));
  tcpmsim::fuzz::expect_clean_outcome(
      [&] { tcpmsim::fit::load_fit(fit_file, {}, data_file, 1, units); });
  return 0;
}
