#include "analysis/coil_fit_command.h"

#include <algorithm>

#include "analysis/coil_fit_analysis.h"
#include "analysis/coil_fit_report.h"

namespace tcpmsim::analysis {

namespace {
// The data directory the analysis read: --data, or the springs' own (each once, in order).
std::string data_directories(const CoilFitOptions& options,
                             const std::vector<CoilSpring>& springs) {
  if (!options.data_directory.empty()) return options.data_directory;
  std::vector<std::string> directories;
  for (const auto& spring : springs) {
    if (std::find(directories.begin(), directories.end(), spring.data_directory) ==
        directories.end())
      directories.push_back(spring.data_directory);
  }
  std::string listed;
  for (const auto& directory : directories) listed += (listed.empty() ? "" : ", ") + directory;
  return listed;
}
}  // namespace

std::string run_coil_fit(const CoilFitOptions& options, std::ostream& out,
                         std::shared_ptr<const UnitSystem> units) {
  std::vector<CoilSpring> springs;
  for (const auto& file : options.spring_files) springs.push_back(load_coil_spring(file, units));
  const auto results = analyse_coil_springs(springs, options.data_directory);
  if (!options.quiet) print_coil_fit_report(out, results);

  const std::string output = options.output.empty() ? "results/coil_fit.h5" : options.output;
  write_coil_fit_hdf5(
      output, results,
      {data_directories(options, springs), options.spring_files, options.invocation});
  if (!options.quiet) out << "\nwrote " << output << "\n";
  return output;
}

}  // namespace tcpmsim::analysis
