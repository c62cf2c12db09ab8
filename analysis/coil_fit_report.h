#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "analysis/coil_fit_analysis.h"

namespace tcpmsim::analysis {

// Thesis Tables 2.2 and 2.3 as computed, each cell next to the published value, the fitted
// parameters, and the chapter-3 comparison of resistance and inductance sensitivity.
void print_coil_fit_report(std::ostream& out, const std::vector<SequenceAnalysis>& results);

struct CoilFitProvenance {
  std::string data_directory;
  std::vector<std::string> spring_files;
  std::string command_line;
};

// Everything to one HDF5 file (layout in the README's coil-spring section).
void write_coil_fit_hdf5(const std::string& path, const std::vector<SequenceAnalysis>& results,
                         const CoilFitProvenance& provenance);

}  // namespace tcpmsim::analysis
