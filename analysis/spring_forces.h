#pragma once

#include "sim/io/hdf5_writer.h"

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "sim/config/units.h"
#include "sim/integrator.h"

namespace tcpmsim {

// Thesis Table 4.2: how far the forces seen by three sensors on an oscillating coil spring stray
// from the massless-spring force F_x = k x: F_i and F_o (load cells at the ends, (4.7)) and F_L
// (inductance, (4.13)). Root mean squared and maximum differences over an analysis window,
// relative to F_nom = k (l_max - l0) (4.14), in percent. The maximum is signed, max(F - F_x):
// the thesis' F_L at omega_1 (RMSD 0.34 %, maximum 0.00 %) only fits a signed maximum.
struct ForceDifferences {
  std::array<double, 3> rms;      // F_i, F_o, F_L [% of F_nom]
  std::array<double, 3> maximum;  // signed [% of F_nom]
};

struct SpringForceRow {
  std::string scenario;
  ForceDifferences simulated;
  // Table 4.2, where the scenario is one of its rows; NaN where the OCR lost a value.
  std::optional<ForceDifferences> thesis;
  SolverStatistics statistics;
  double wall_seconds = 0.0;
  double nominal_force = 0.0;  // F_nom [N]
};

// Runs chapter-4 spring scenarios (each needs a spring with an inductance section) on `threads`
// threads and analyses the last `window` seconds of each. Results do not depend on the number
// of threads.
std::vector<SpringForceRow> run_spring_forces(const std::vector<std::string>& configs,
                                              double window, int threads,
                                              std::shared_ptr<const UnitSystem> units);

// Table 4.2 as published, by scenario name (ch4_st_heel_strike, ...); NaN marks the value the
// OCR lost.
std::optional<ForceDifferences> thesis_table_4_2(const std::string& scenario);

std::string format_spring_force_table(const std::vector<SpringForceRow>& rows);
void write_spring_force_table(const std::vector<SpringForceRow>& rows, const std::string& path,
                              const Provenance& provenance);

}  // namespace tcpmsim
