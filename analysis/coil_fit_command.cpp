#include "analysis/coil_fit_command.h"

#include "analysis/coil_fit_analysis.h"
#include "analysis/coil_fit_report.h"

namespace tcpmsim::analysis {

std::string run_coil_fit(const CoilFitOptions& options, std::ostream& out,
                         std::shared_ptr<const UnitSystem> units) {
  std::vector<CoilSpring> springs;
  for (const auto& file : options.spring_files) springs.push_back(load_coil_spring(file, units));
  const auto results = analyse_coil_springs(springs, options.data_directory);
  if (!options.quiet) print_coil_fit_report(out, results);

  const std::string output = options.output.empty() ? "results/coil_fit.h5" : options.output;
  write_coil_fit_hdf5(output, results, {options.data_directory, options.spring_files});
  if (!options.quiet) out << "\nwrote " << output << "\n";
  return output;
}

}  // namespace tcpmsim::analysis
