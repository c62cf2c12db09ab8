#pragma once

#include <Eigen/Dense>

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "identification/fit_problem.h"

namespace tcpmsim::fit {

// How the fit differentiates the residuals: forward sensitivities (CVODES) where the model
// allows them, else forward differences of whole simulations (automatic); or one of the two.
enum class Gradient { automatic, sensitivities, differences };

struct FitSettings {
  // Multistart: `starts` Latin-hypercube points over the bounds (seeded) are screened by one
  // simulation each, besides the model's own values; Levenberg-Marquardt refines the `refine`
  // best of them, and the best refined result is the estimate.
  int starts = 8;
  int refine = 1;
  // Refine only the drawn points, never the first (discover's retry of a candidate whose refit
  // never left its nested start, where the effect's shape parameters have no gradient).
  bool drawn_starts_only = false;
  // The multistart draws the parameters from this index on; those before it start at the
  // model's values in every point (discover's candidates: the base model as fitted).
  std::size_t screened_from = 0;
  // Where the fit starts (SI, one value per parameter): the first point, and the value of every
  // parameter before screened_from in each start. Empty: the model's own values. (discover's
  // candidates start where the effect has zero size, so that each is the base model there.)
  std::vector<double> start;
  std::uint64_t seed = 1;
  int threads = 2;  // simulations at once (finite differences, screening)
  // The forward-sensitivity runs the parameters are shared among (alternately), whatever the
  // thread count: CVODES controls its steps on the states and the sensitivities it carries
  // together, so a grouping that followed the threads would move the estimates with -j (by some
  // 1e-8). Two: what the default two threads run at once.
  int sensitivity_groups = 2;
  double difference_step = 1e-4;  // of each parameter's bound range, for forward differences
  int max_iterations = 50;
  // Levenberg-Marquardt stops when an iteration lowers the cost by less than this fraction.
  double function_tolerance = 1e-8;
  Gradient gradient = Gradient::automatic;
};

// One parameter's estimate. standard_error is NaN when the data do not fix it at all (outside
// the Jacobian's rank); a parameter correlated above 0.99 with another, or whose standard error
// exceeds its estimate, keeps its standard error but is not identifiable either.
struct ParameterEstimate {
  std::string path;
  std::string unit;
  double initial = 0.0;
  double value = 0.0;
  double standard_error = 0.0;
  bool identifiable = true;
  // "lower" or "upper" when the estimate ended on that bound, where the optimum may lie beyond
  // it and its standard error means little; "" inside.
  std::string at_bound;
};

// How well the model fits the measurement in a window, per output: RMSE [unit], NRMSE (RMSE
// over the measured range), R^2 (1 - SSE/SST).
struct WindowScore {
  std::vector<double> rmse;
  std::vector<double> nrmse;
  std::vector<double> r2;
  std::size_t samples = 0;
};

struct FitResult {
  std::vector<ParameterEstimate> estimates;
  Eigen::MatrixXd correlation;  // of the estimates (NaN rows for unidentified ones)
  int rank = 0;                 // of the weighted Jacobian at the optimum
  // Why parameters were not identified: "k1 and k2 are correlated (-0.9995)", "c does not
  // change the outputs (rank 5 of 6)".
  std::vector<std::string> identifiability;
  double cost = 0.0;               // 1/2 sum of squared weighted residuals at the estimate
  double start_cost = 0.0;         // the same at the first starting point
  std::size_t refined_start = 0;   // the starting point the estimate was refined from (0: first)
  double residual_variance = 0.0;  // 2 cost / (samples - parameters)
  int iterations = 0;
  int simulations = 0;
  std::string termination;
  // false when Levenberg-Marquardt stopped at its iteration limit (max_iterations) before any
  // of its tolerances was met: the estimate is the best found, not an optimum.
  bool converged = true;
  // How the Jacobian was computed: "forward sensitivities (CVODES)", or "finite differences"
  // with the reason sensitivities were not used.
  std::string gradient;
  WindowScore identification;
  WindowScore validation;
};

// The model could not be simulated where the fit needed it (at every starting point, or around
// the estimate); the message says why, from the first failure.
class FitFailure : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Levenberg-Marquardt (Ceres) from a seeded multistart, with forward-difference gradients run
// as parallel simulations; standard errors and correlations from the Jacobian at the optimum.
FitResult fit_model(const FitProblem& problem, const FitSettings& settings);

// The scores of the model at `values` in `window`.
WindowScore score_window(const FitProblem& problem, const std::vector<double>& values,
                         const TimeWindow& window);

}  // namespace tcpmsim::fit
