#include "tests/support/discover_data.h"

#include <filesystem>
#include <fstream>

#include "identification/bench_measurement.h"
#include "sim/scenario.h"
#include "tests/support/test_support.h"

namespace tcpmsim::testing {

namespace {
const std::string kBase = "configs/discover/ch7_base.yaml";
}  // namespace

std::string discover_measurement(const std::string& name, std::vector<std::string> hidden,
                                 const std::string& duration, std::uint64_t bench_seed) {
  // The protocol cut to 200 s of multisines to identify and 100 s of random steps to validate,
  // to keep the suite quick; the whole protocol is scripts/discover_matrix.py's.
  hidden.push_back("measurement.file=" + protocol_record(duration));
  hidden.push_back("scenario.duration=" + duration);
  const Scenario truth = load_scenario(source_path(kBase), hidden, shared_units());
  auto bench =
      fit::load_bench(source_path("configs/discover/ch7_bench.yaml"), truth, shared_units());
  bench.seed = bench_seed;
  const std::string path =
      (std::filesystem::path(process_directory("discover")) / (name + ".csv")).string();
  std::ofstream(path) << fit::measure(truth, bench, *shared_units());
  return path;
}

fit::DiscoverRequest discover_request(const std::string& data, std::vector<std::string> effects) {
  fit::DiscoverRequest request;
  request.max_order = 1;
  request.starts = 2;
  request.model_file = source_path(kBase);
  request.data_file = data;
  request.inputs = {"power", "deflection"};
  request.outputs = {"force"};
  request.validate_from = 200.0;
  request.effects = std::move(effects);
  return request;
}

fit::DiscoverRequest short_hysteresis_request() {
  const std::string data = discover_measurement(
      "hysteresis_short", {"muscle.effects=[{type: hysteresis, stiffness: 50 N/m, force: 6 mN}]"},
      "120 s");
  auto request = discover_request(data, {"hysteresis"});
  request.validate_from = 80.0;
  request.starts = 1;
  return request;
}

std::vector<std::string> candidate_names(const fit::Candidates& candidates) {
  std::vector<std::string> names;
  for (const auto& candidate : candidates.candidates) names.push_back(candidate.name);
  return names;
}

}  // namespace tcpmsim::testing
