#pragma once

#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "sim/config/units.h"

namespace tcpmsim {

struct SpringForcesOptions {
  std::vector<std::string> configs;  // chapter-4 scenarios
  std::string output;                // HDF5; empty: results/spring_forces.h5
  double window = 0.25;              // analysed tail of each run [s]
  int threads = 2;
  bool quiet = false;
  std::string invocation;  // the command line, for the file's provenance
};

// `tcpmsim spring-forces`: runs the scenarios, prints Table 4.2 beside the thesis' values and,
// for each distinct spring, its eigenfrequencies and force transmissibility against the
// continuum (4.1)-(4.3); writes the table to HDF5. Returns the output path.
std::string run_spring_forces_command(const SpringForcesOptions& options, std::ostream& out,
                                      std::shared_ptr<const UnitSystem> units);

}  // namespace tcpmsim
