#include "analysis/control_tasks_command.h"

#include <chrono>
#include <cstdio>

#include "analysis/pair_task_runner.h"
#include "analysis/provenance.h"

namespace tcpmsim {

std::string run_control_tasks_command(const ControlTasksOptions& options, std::ostream& out,
                                      std::shared_ptr<const UnitSystem> units) {
  const auto started = std::chrono::steady_clock::now();
  // Joint-angle tasks of a pair go to their own runner; the rest are single-muscle tasks.
  std::vector<std::string> single_configs, pair_configs;
  for (const auto& config : options.configs)
    (is_pair_task(config, options.settings.overrides, units) ? pair_configs : single_configs)
        .push_back(config);
  // The pair tasks first: they check themselves before anything runs.
  const auto pair_results = run_pair_tasks(pair_configs, options.settings, units);
  const auto results = run_control_tasks(single_configs, options.settings, units);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  const std::string output = options.output.empty() ? "results/control_tasks.h5" : options.output;
  write_control_task_report(
      results, output,
      file_provenance(options.invocation, options.configs, options.settings.overrides, units),
      [&](Hdf5Writer& file) { write_pair_tasks(file, pair_results); });
  if (!options.quiet) {
    if (!results.empty()) out << format_control_task_report(results);
    if (!pair_results.empty()) out << format_pair_comparison(pair_results, results);
    char line[128];
    std::snprintf(line, sizeof line, "\n%zu tasks (with their calibrations) in %.2f s\nwrote ",
                  results.size() + pair_results.size(), seconds);
    out << line << output << "\n";
  }
  return output;
}

}  // namespace tcpmsim
