// Times the full Table 4.2 set (the ten chapter-4 scenarios), reading the scenarios and
// integrating them, on 1 and on 2 threads. Prints key=value pairs.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "analysis/spring_forces.h"

int main(int argc, char** argv) {
  const std::string folder = argc > 1 ? argv[1] : "configs/ch4";
  std::vector<std::string> configs;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    if (entry.path().extension() == ".yaml") configs.push_back(entry.path().string());
  }
  std::sort(configs.begin(), configs.end());
  const auto units = std::make_shared<tcpmsim::UnitSystem>();
  for (int threads : {1, 2}) {
    std::vector<double> seconds;
    long steps = 0;
    for (int repeat = 0; repeat < 3; ++repeat) {
      const auto started = std::chrono::steady_clock::now();
      const auto rows = tcpmsim::run_spring_forces(configs, 0.25, threads, units);
      seconds.push_back(
          std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count());
      steps = 0;
      for (const auto& row : rows) steps += row.statistics.steps;
    }
    std::sort(seconds.begin(), seconds.end());
    std::printf(
        "table_4_2 simulations=%zu threads=%d median_seconds=%.3f min_seconds=%.3f steps=%ld\n",
        configs.size(), threads, seconds[1], seconds[0], steps);
  }
  return 0;
}
