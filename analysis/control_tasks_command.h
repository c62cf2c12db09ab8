#pragma once

#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "analysis/control_task_runner.h"

namespace tcpmsim {

struct ControlTasksOptions {
  std::vector<std::string> configs;
  std::string output;      // HDF5; empty: results/control_tasks.h5
  std::string invocation;  // the command line, for the file's provenance
  ControlTaskSettings settings;
  bool quiet = false;
};

// `tcpmsim control-tasks`: calibrates and runs the chapter-7 control tasks, prints the thesis
// comparison and writes it to HDF5. Returns the output path.
std::string run_control_tasks_command(const ControlTasksOptions& options, std::ostream& out,
                                      std::shared_ptr<const UnitSystem> units);

}  // namespace tcpmsim
