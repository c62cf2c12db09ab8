// Times the integration of a scenario in-process: CVODE plus the evaluation of every output
// at every sample time into memory, the work SciPy's solve_ivp does in the reference script.
// Excludes process start-up, reading the scenario and writing HDF5 (timed separately by the
// benchmark script, end to end). Prints one line of key=value pairs.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <vector>

#include "kinds/standard_kinds.h"

namespace {
class KeepEverything final : public tcpmsim::OutputSink {
 public:
  void record(double time, std::span<const double> signals) override {
    values.push_back(time);
    values.insert(values.end(), signals.begin(), signals.end());
  }
  std::vector<double> values;
};
}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: bench_integration CONFIG [REPEATS] [KEY=VALUE ...]\n");
    return 2;
  }
  const int repeats = argc > 2 ? std::atoi(argv[2]) : 20;
  std::vector<std::string> overrides(argv + std::min(argc, 3), argv + argc);
  const auto units = std::make_shared<tcpmsim::UnitSystem>();
  std::vector<double> seconds;
  tcpmsim::SolverStatistics statistics;
  int states = 0;
  for (int k = 0; k < repeats; ++k) {
    tcpmsim::Scenario scenario = tcpmsim::load_scenario(argv[1], overrides, units);
    KeepEverything sink;
    sink.values.reserve(1 << 20);
    states = scenario.system->state_size();
    tcpmsim::Context context = scenario.make_context();
    tcpmsim::Integrator integrator(*scenario.system, context, scenario.solver);
    const auto started = std::chrono::steady_clock::now();
    statistics =
        integrator.run(0.0, scenario.settings.duration,
                       {scenario.settings.output_interval, scenario.settings.output_start}, sink);
    seconds.push_back(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count());
  }
  std::sort(seconds.begin(), seconds.end());
  std::printf(
      "median_seconds=%.6g min_seconds=%.6g steps=%ld rhs=%ld jacobians=%ld segments=%ld "
      "samples=%ld states=%d\n",
      seconds[seconds.size() / 2], seconds.front(), statistics.steps, statistics.rhs_evaluations,
      statistics.jacobian_evaluations, statistics.segments, statistics.output_samples, states);
  return 0;
}
