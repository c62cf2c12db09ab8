#pragma once

#include <memory>
#include <string>
#include <vector>

#include "models/inductance/coil_geometry.h"
#include "sim/config/config_error.h"
#include "sim/config/config_node.h"

namespace tcpmsim::analysis {

// A tension spring of the chapter-2 experiment (thesis Table 2.1), read from its YAML file
// (configs/springs/s1.yaml ...), with the measurement sequences that belong to it.
struct CoilSpring {
  std::string name;
  std::string source;           // the YAML file
  double wire_diameter = 0.0;   // delta [m]
  double outer_diameter = 0.0;  // [m] (callipers)
  double body_length = 0.0;     // Lb [m]
  double turns = 0.0;           // N; default the close-wound Lc / delta
  struct Sequence {
    std::string name;         // file stem in the data directory
    SourceLocation location;  // where the YAML names it
  };
  std::vector<Sequence> sequences;
  std::string calibration;  // the sequence whose fit (2.14) the others reuse
  // Where the sequences' files <name>.csv are: the spring file's `data`, taken from the spring
  // file's directory like any file a configuration names; default that directory itself.
  std::string data_directory;

  double radius() const { return 0.5 * (outer_diameter - wire_diameter); }  // r = Dm / 2
  double coil_length() const { return body_length - wire_diameter; }        // Lc = Lb - delta
  // The coil stretched to `length`.
  inductance::CoilGeometry at_length(double length) const {
    return {radius(), length, turns, wire_diameter};
  }

  static CoilSpring from_config(const ConfigNode& root);
};

CoilSpring load_coil_spring(const std::string& file, std::shared_ptr<const UnitSystem> units);

}  // namespace tcpmsim::analysis
