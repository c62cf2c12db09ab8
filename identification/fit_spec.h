#pragma once

#include <memory>
#include <string>
#include <vector>

#include "identification/fit_problem.h"
#include "identification/output_error_fit.h"
#include "sim/config/units.h"

namespace tcpmsim::fit {

// A fit file, read:
//   model: ch7_base.yaml            # a scenario whose data signals replay the measurement
//   set: [muscle.mechanics.k1=12 mN/mm]   # optional: the model's starting values, changed
//   data: bench.csv                 # the measurement (the command's --data replaces it)
//   outputs:                        # measured channel, the model output it is compared with,
//     - {channel: force, output: load.force, noise: 1 mN}    # and the measurement's noise
//   parameters:                     # by path, within bounds in any unit of the parameter's
//     - {path: muscle.mechanics.k1, bounds: [5 N/m, 20 N/m]}
//   identification: [0 s, 400 s]    # the window fitted
//   validation: [400 s, 620 s]      # optional: the window only scored
//   multistart: {starts: 8, refine: 2, seed: 1}
// Files are found beside the fit file. The model runs over the windows (its scenario.duration
// is set to their end) with its measurement.file set to the data.
struct FitSpec {
  std::string file;  // the fit file; empty for a spec `tcpmsim discover` made
  std::string model_file;
  std::string data_file;
  FitProblem problem;
  FitSettings settings;
};

// Why `model` cannot be compared with `data` from time `from` on: it records less often than
// the data are sampled, or only after `from`; "" when it can. The remedy is written as
// set_before + "output.rate=16 Hz" + set_after.
std::string output_rate_problem(const Scenario& model, const MeasuredData& data, double from,
                                std::string_view set_before, std::string_view set_after);

FitSpec load_fit(const std::string& file, const std::vector<std::string>& overrides,
                 const std::string& data_override, int threads,
                 std::shared_ptr<const UnitSystem> units);

}  // namespace tcpmsim::fit
