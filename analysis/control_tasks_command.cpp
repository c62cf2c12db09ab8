#include "analysis/control_tasks_command.h"

#include <chrono>
#include <cstdio>

namespace tcpmsim {

std::string run_control_tasks_command(const ControlTasksOptions& options, std::ostream& out,
                                      std::shared_ptr<const UnitSystem> units) {
  const auto started = std::chrono::steady_clock::now();
  const auto results = run_control_tasks(options.configs, options.settings, std::move(units));
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  const std::string output = options.output.empty() ? "results/control_tasks.h5" : options.output;
  write_control_task_report(results, output);
  if (!options.quiet) {
    out << format_control_task_report(results);
    char line[128];
    std::snprintf(line, sizeof line, "\n%zu tasks (with their calibrations) in %.2f s\nwrote ",
                  results.size(), seconds);
    out << line << output << "\n";
  }
  return output;
}

}  // namespace tcpmsim
