#pragma once

#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "sim/config/units.h"

namespace tcpmsim::analysis {

struct CoilFitOptions {
  std::vector<std::string> spring_files;  // configs/springs/s1.yaml ...
  std::string data_directory;             // holds <sequence>.csv; empty: each spring's own
  std::string output;                     // HDF5; empty: results/coil_fit.h5
  std::string invocation;                 // the command line, for the file's provenance
  bool quiet = false;                     // no tables on `out`
};

// `tcpmsim coil-fit`: reads the springs and their sequences, runs the chapter-2/3 analysis,
// prints the tables to `out` and writes the HDF5 file. Bad input throws ConfigError (located);
// an unwritable output throws std::runtime_error. Returns the output path.
std::string run_coil_fit(const CoilFitOptions& options, std::ostream& out,
                         std::shared_ptr<const UnitSystem> units);

}  // namespace tcpmsim::analysis
