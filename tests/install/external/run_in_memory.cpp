// Runs a scenario file in memory through the installed library and writes its record:
//   run_in_memory CONFIG OUTPUT.h5
#include <exception>
#include <iostream>
#include <memory>

#include "kinds/standard_kinds.h"
#include "sim/memory_run.h"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: run_in_memory CONFIG OUTPUT.h5\n";
    return 2;
  }
  try {
    const tcpmsim::Scenario scenario =
        tcpmsim::load_scenario(argv[1], {}, std::make_shared<tcpmsim::UnitSystem>());
    const tcpmsim::MemoryRun run = tcpmsim::run_in_memory(scenario);
    std::cout << run.status << ": " << run.time.size() << " samples\n";
    tcpmsim::save_record(scenario, run, argv[2]);
    return run.status == "complete" ? 0 : 1;
  } catch (const std::exception& error) {
    std::cerr << error.what() << "\n";
    return 1;
  }
}
