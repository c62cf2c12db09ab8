#pragma once

#include <string>
#include <vector>

#include "analysis/coil_models.h"
#include "analysis/coil_sequence.h"
#include "analysis/coil_spring.h"
#include "analysis/impedance_sensitivity.h"
#include "models/inductance/spring_inductance_fit.h"

namespace tcpmsim::analysis {

// One model's account of one sequence (thesis section 2.3.3).
struct ModelOutcome {
  std::string key;                           // HDF5 name: basic ... neumann_helix, fitted
  std::string title;                         // table heading
  std::vector<double> inductance;            // at the measured lengths [H]
  std::vector<double> table_inductance;      // at the 25 table lengths [H]
  std::vector<double> predicted_deflection;  // from the measured mean inductance [m]
  double r_squared = 0.0;                    // (2.15), measured mean L against the model
  double rmse_fraction = 0.0;                // RMSE of the deflection / its range
  // Why the table has no inverse (its inductance turns, or stays, as the coil is stretched: a
  // geometry outside the model), when it has none; the predicted deflection is then NaN.
  std::string not_invertible;
};

struct SequenceAnalysis {
  std::string spring;
  std::string sequence;
  std::string calibration;  // the sequence the fitted model was calibrated on
  double wire_diameter = 0.0, radius = 0.0, coil_length = 0.0, turns = 0.0;
  CoilSequence kept;               // the steps analysed (free-length line dropped)
  std::vector<double> deflection;  // [m]
  std::vector<double> length;      // Lc + deflection [m]
  std::vector<double> inductance_mean, inductance_std;  // [H]
  std::vector<double> table_length, table_deflection;   // Lc linspace(1, 1.55, 25) [m]
  std::vector<ModelOutcome> models;  // kCoilModels order, then the fitted model last
  inductance::SpringInductanceFit fit;
  ImpedanceSensitivity resistance, inductance;  // chapter 3
};

// The thesis' protocol (physics.md section 1): drop the free-length line; fit (2.14) on the
// first and last remaining step of each spring's calibration sequence and reuse it for the
// spring's other sequences; R^2 of the measured mean inductance against every model at the
// measured lengths; deflection from the measured mean inductance by the inverse fit or, for the
// theoretical models, by linear inter/extrapolation in a 25-point table over
// Lc linspace(1, 1.55, 25); RMSE relative to the deflection range. Sequence files are
// <data_directory>/<name>.csv, or with an empty `data_directory` in each spring's own
// (CoilSpring::data_directory); a missing one is reported at the YAML line that names it.
std::vector<SequenceAnalysis> analyse_coil_springs(const std::vector<CoilSpring>& springs,
                                                   const std::string& data_directory);

// One sequence with a given calibration (exposed for tests).
SequenceAnalysis analyse_sequence(const CoilSpring& spring, const CoilSequence& kept,
                                  const inductance::SpringInductanceFit& fit,
                                  const std::string& calibration);

// The two-point calibration of (2.14) on a sequence's first and last kept step.
inductance::SpringInductanceFit calibrate(const CoilSpring& spring, const CoilSequence& kept);

inline constexpr std::size_t kTablePoints = 25;
inline constexpr double kTableStretch = 1.55;

}  // namespace tcpmsim::analysis
