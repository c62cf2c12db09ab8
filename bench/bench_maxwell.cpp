// Times one Maxwell summation (4.11) over N = 52 non-uniform winding positions (spring S_T of
// Table 4.1): the table-driven MaxwellEvaluator against the direct elliptic-integral sum, in one
// process, and reports their largest relative difference. Prints key=value pairs.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>

#include "models/inductance/loop_mutual.h"
#include "models/inductance/maxwell.h"
#include "models/inductance/maxwell_evaluator.h"
#include "sim/random_stream.h"

namespace {
template <typename F>
double median_microseconds(int repeats, int calls, F&& f) {
  std::vector<double> times;
  for (int r = 0; r < repeats; ++r) {
    const auto started = std::chrono::steady_clock::now();
    for (int c = 0; c < calls; ++c) f(c);
    times.push_back(
        std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - started)
            .count() /
        calls);
  }
  std::sort(times.begin(), times.end());
  return times[times.size() / 2];
}
}  // namespace

int main() {
  using namespace tcpmsim;
  const int windings = 52;
  const double radius = 0.008, wire = 0.002, length = 0.230;
  const double gmd = inductance::wire_gmd(wire);
  const inductance::MaxwellEvaluator evaluator(radius, gmd, 0.05 * wire, 2 * 0.264);
  // 64 configurations of a vibrating spring: uniform windings displaced by up to 20 % of a gap.
  RandomStream stream(52, "bench_maxwell");
  std::vector<std::vector<double>> configurations(64, std::vector<double>(windings));
  for (auto& positions : configurations) {
    for (int i = 0; i < windings; ++i) {
      positions[static_cast<std::size_t>(i)] =
          (i + 0.5) * length / windings + stream.uniform(-0.2, 0.2) * length / windings;
    }
  }
  double sink = 0.0, worst = 0.0;
  for (const auto& positions : configurations) {
    const double fast = evaluator.inductance(positions);
    const double direct = inductance::maxwell_positions(radius, gmd, positions);
    worst = std::max(worst, std::abs(fast - direct) / direct);
  }
  const double fast_us = median_microseconds(9, 2000, [&](int c) {
    sink += evaluator.inductance(configurations[static_cast<std::size_t>(c % 64)]);
  });
  const double direct_us = median_microseconds(5, 100, [&](int c) {
    sink += inductance::maxwell_positions(radius, gmd,
                                          configurations[static_cast<std::size_t>(c % 64)]);
  });
  std::printf(
      "maxwell N=%d: evaluator_us=%.3f direct_us=%.2f speedup=%.1f max_relative_difference=%.2e "
      "(checksum %.3e)\n",
      windings, fast_us, direct_us, direct_us / fast_us, worst, sink);
  return 0;
}
