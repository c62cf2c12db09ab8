// A scenario whose controller is the user's relay (relay_controller.h), run through the
// installed library with the standard kinds plus that one, its record written:
//   run_with_relay CONFIG OUTPUT.h5 [KEY.PATH=VALUE ...]
#include <exception>
#include <iostream>
#include <memory>

#include "kinds/standard_kinds.h"
#include "relay_controller.h"
#include "sim/memory_run.h"

int main(int argc, char** argv) {
  if (argc < 3) {
    std::cerr << "usage: run_with_relay CONFIG OUTPUT.h5 [KEY.PATH=VALUE ...]\n";
    return 2;
  }
  try {
    tcpmsim::KindRegistry kinds = tcpmsim::standard_kinds();
    consumer::register_relay_controller(kinds);
    const std::vector<std::string> overrides(argv + 3, argv + argc);
    const tcpmsim::Scenario scenario =
        tcpmsim::load_scenario(argv[1], overrides, std::make_shared<tcpmsim::UnitSystem>(), kinds);
    const tcpmsim::MemoryRun run = tcpmsim::run_in_memory(scenario);
    std::cout << run.status << ": " << run.time.size() << " samples\n";
    tcpmsim::save_record(scenario, run, argv[2]);
    return run.status == "complete" ? 0 : 1;
  } catch (const std::exception& error) {
    std::cerr << error.what() << "\n";
    return 1;
  }
}
