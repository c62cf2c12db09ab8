#include "identification/output_error_fit.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <mutex>
#include <numeric>
#include <stdexcept>

#include "sim/not_a_number.h"
#include "sim/parallel_runs.h"
#include "sim/value_check.h"
#include "sweep/sweep_design.h"

namespace tcpmsim::fit {

namespace {

// The parameters in SI from the optimiser's coordinates: each bound range mapped to [0, 1].
std::vector<double> physical(const FitProblem& problem, const double* unit_values) {
  std::vector<double> values;
  for (std::size_t j = 0; j < problem.parameters.size(); ++j) {
    const auto& parameter = problem.parameters[j];
    values.push_back(parameter.lower + unit_values[j] * (parameter.upper - parameter.lower));
  }
  return values;
}

// Weighted residuals (model - measured) / noise at the identification samples, output by
// output; false if the model cannot run there.
class Residuals {
 public:
  explicit Residuals(const FitProblem& problem)
      : problem_(problem), measured_(measured_outputs(problem, problem.identification)) {
    for (const auto& series : measured_) count_ += series.size();
  }
  std::size_t count() const { return count_; }

  bool evaluate(const std::vector<double>& values, double* residuals) const {
    ++simulations_;
    std::vector<std::vector<double>> simulated;
    try {
      simulated = simulate_outputs(problem_, values, problem_.identification);
    } catch (const std::exception& error) {
      // A solver failure or a value the model refuses: a step Ceres must reject.
      note_failure(error.what());
      return false;
    }
    std::size_t at = 0;
    for (std::size_t k = 0; k < measured_.size(); ++k) {
      const double noise = problem_.outputs[k].noise;
      for (std::size_t i = 0; i < measured_[k].size(); ++i) {
        residuals[at++] = (simulated[k][i] - measured_[k][i]) / noise;
        if (!std::isfinite(residuals[at - 1])) {
          note_failure(residual_problem(k, i, "is not a finite number",
                                        ", simulated " + number_text(simulated[k][i])));
          return false;
        }
      }
    }
    return true;
  }
  double cost(const std::vector<double>& values) const {
    std::vector<double> residuals(count_);
    if (!evaluate(values, residuals.data())) return std::numeric_limits<double>::infinity();
    const double cost =
        0.5 * std::inner_product(residuals.begin(), residuals.end(), residuals.begin(), 0.0);
    if (!std::isfinite(cost)) note_failure(largest_residual_problem(residuals));
    return cost;
  }
  // The weighted residuals' Jacobian (row-major, m x n) per SI unit of each parameter, from
  // forward sensitivities; the parameters are shared among `groups` runs, `threads` at once.
  bool sensitivity_jacobian(const std::vector<double>& values, int groups, int threads,
                            std::vector<double>& jacobian) const {
    const std::size_t n = values.size();
    const auto runs = std::min<std::size_t>(n, static_cast<std::size_t>(std::max(1, groups)));
    std::vector<std::vector<std::size_t>> tracked(runs);
    for (std::size_t j = 0; j < n; ++j) tracked[j % runs].push_back(j);
    std::vector<OutputSensitivities> results(runs);
    std::vector<char> ran(runs, 0);
    const std::vector<std::string> labels(runs, "sensitivities");
    run_in_parallel(labels, threads, [&](std::size_t r) {
      ++simulations_;
      try {
        results[r] = simulate_sensitivities(problem_, values, tracked[r], problem_.identification);
        ran[r] = 1;
      } catch (const std::exception& error) {
        note_failure(error.what());
      }
    });
    if (std::find(ran.begin(), ran.end(), 0) != ran.end()) return false;
    jacobian.assign(count_ * n, 0.0);
    for (std::size_t r = 0; r < runs; ++r) {
      for (std::size_t t = 0; t < tracked[r].size(); ++t) {
        std::size_t at = 0;
        for (std::size_t k = 0; k < measured_.size(); ++k) {
          const auto& column = results[r].sensitivities[k][t];
          for (double value : column)
            jacobian[(at++) * n + tracked[r][t]] = value / problem_.outputs[k].noise;
        }
      }
    }
    return std::all_of(jacobian.begin(), jacobian.end(), [](double v) { return std::isfinite(v); });
  }
  int simulations() const { return simulations_; }
  std::string first_failure() const {
    const std::lock_guard lock(mutex_);
    return first_failure_;
  }

 private:
  void note_failure(const std::string& failure) const {
    const std::lock_guard lock(mutex_);
    if (first_failure_.empty()) first_failure_ = failure;
  }
  // What is wrong with residual i of output k ("is not a finite number"), with the values.
  std::string residual_problem(std::size_t k, std::size_t i, const std::string& wrong,
                               const std::string& values) const {
    const FitOutput& output = problem_.outputs[k];
    const std::size_t sample = samples_in(*problem_.data, problem_.identification).first + i;
    return "the residual of " + output.output + " against the measured " + output.channel +
           " at t = " + number_text(problem_.data->time()[sample]) + " s " + wrong + " (measured " +
           number_text(measured_[k][i]) + values + " " + output.unit + ", noise " +
           number_text(output.noise) + " " + output.unit + ")";
  }
  // The largest of finite residuals whose squares sum beyond a double.
  std::string largest_residual_problem(const std::vector<double>& residuals) const {
    const auto largest = static_cast<std::size_t>(
        std::max_element(residuals.begin(), residuals.end(),
                         [](double a, double b) { return std::abs(a) < std::abs(b); }) -
        residuals.begin());
    std::size_t k = 0, i = largest;
    while (i >= measured_[k].size()) i -= measured_[k++].size();
    return residual_problem(k, i,
                            "is " + number_text(std::abs(residuals[largest])) +
                                " noise widths: the squared "
                                "residuals overflow",
                            "");
  }

  const FitProblem& problem_;
  std::vector<std::vector<double>> measured_;
  std::size_t count_ = 0;
  mutable std::atomic<int> simulations_{0};
  mutable std::mutex mutex_;
  mutable std::string first_failure_;
};

// The residuals of one simulation and their forward-difference Jacobian in the unit
// coordinates, its columns simulated in parallel.
class SimulationCost final : public ceres::CostFunction {
 public:
  SimulationCost(const FitProblem& problem, const Residuals& residuals, const FitSettings& settings,
                 bool sensitivities)
      : problem_(problem),
        residuals_(residuals),
        settings_(settings),
        sensitivities_(sensitivities) {
    set_num_residuals(static_cast<int>(residuals.count()));
    mutable_parameter_block_sizes()->push_back(static_cast<int>(problem.parameters.size()));
  }

  // Ceres asks for the same point more than once (a bounded step's line search, its cost, then
  // its Jacobian): the last point's residuals and Jacobian are kept and handed out again.
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    const std::size_t n = problem_.parameters.size();
    const std::size_t m = residuals_.count();
    const std::vector<double> theta(parameters[0], parameters[0] + n);
    const bool want_jacobian = jacobians && jacobians[0];
    if (theta != last_theta_) {
      last_theta_.clear();
      last_jacobian_.clear();
      last_residuals_.assign(m, 0.0);
      if (!residuals_.evaluate(physical(problem_, theta.data()), last_residuals_.data()))
        return false;
      last_theta_ = theta;
    }
    std::copy(last_residuals_.begin(), last_residuals_.end(), residuals);
    if (!want_jacobian) return true;
    if (last_jacobian_.empty() && !(sensitivities_ ? sensitivity(theta) : difference(theta)))
      return false;
    std::copy(last_jacobian_.begin(), last_jacobian_.end(), jacobians[0]);
    return true;
  }

 private:
  // The Jacobian at the last point from forward sensitivities, in the unit coordinates.
  bool sensitivity(const std::vector<double>& theta) const {
    if (!residuals_.sensitivity_jacobian(physical(problem_, theta.data()),
                                         settings_.sensitivity_groups, settings_.threads,
                                         last_jacobian_))
      return false;
    const std::size_t n = theta.size();
    for (std::size_t i = 0; i < last_jacobian_.size(); ++i) {
      const auto& parameter = problem_.parameters[i % n];
      last_jacobian_[i] *= parameter.upper - parameter.lower;
    }
    return true;
  }

  // The forward-difference Jacobian at the last point (row-major), its columns in parallel.
  bool difference(const std::vector<double>& theta) const {
    const std::size_t n = theta.size();
    const std::size_t m = residuals_.count();
    std::vector<std::vector<double>> columns(n, std::vector<double>(m));
    std::vector<double> steps(n);
    std::vector<char> ran(n, 0);
    const std::vector<std::string> labels(n, "finite difference");
    run_in_parallel(labels, settings_.threads, [&](std::size_t j) {
      std::vector<double> shifted = theta;
      // Forward, or backward at the upper bound, by a fixed fraction of the range.
      steps[j] = theta[j] + settings_.difference_step <= 1.0 ? settings_.difference_step
                                                             : -settings_.difference_step;
      shifted[j] += steps[j];
      ran[j] = residuals_.evaluate(physical(problem_, shifted.data()), columns[j].data());
    });
    if (std::find(ran.begin(), ran.end(), 0) != ran.end()) return false;
    last_jacobian_.resize(m * n);
    for (std::size_t i = 0; i < m; ++i) {
      for (std::size_t j = 0; j < n; ++j)
        last_jacobian_[i * n + j] = (columns[j][i] - last_residuals_[i]) / steps[j];
    }
    return true;
  }

  const FitProblem& problem_;
  const Residuals& residuals_;
  const FitSettings& settings_;
  bool sensitivities_;
  mutable std::vector<double> last_theta_;
  mutable std::vector<double> last_residuals_;
  mutable std::vector<double> last_jacobian_;
};

// Where an estimate (scaled to its bounds, [0, 1]) ended: "lower", "upper" or "" inside. The
// bounded trust region projects its steps onto the bounds, so an estimate there sits on them.
std::string bound_reached(double scaled) {
  constexpr double kOnBound = 1e-9;
  return scaled <= kOnBound ? "lower" : scaled >= 1.0 - kOnBound ? "upper" : "";
}

struct Refined {
  std::vector<double> theta;
  double cost = 0.0;
  int iterations = 0;
  std::string termination;
  bool converged = true;
};

Refined refine(const FitProblem& problem, const Residuals& residuals, const FitSettings& settings,
               bool sensitivities, std::vector<double> theta) {
  ceres::Problem ceres_problem;
  ceres_problem.AddResidualBlock(new SimulationCost(problem, residuals, settings, sensitivities),
                                 nullptr, theta.data());
  for (std::size_t j = 0; j < theta.size(); ++j) {
    ceres_problem.SetParameterLowerBound(theta.data(), static_cast<int>(j), 0.0);
    ceres_problem.SetParameterUpperBound(theta.data(), static_cast<int>(j), 1.0);
  }
  ceres::Solver::Options options;
  options.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  options.linear_solver_type = ceres::DENSE_QR;
  options.max_num_iterations = settings.max_iterations;
  options.function_tolerance = settings.function_tolerance;
  options.parameter_tolerance = 1e-8;
  options.gradient_tolerance = 1e-12;
  options.logging_type = ceres::SILENT;
  // The projected step of a bounded problem is searched with Armijo; cubic interpolation would
  // ask for a Jacobian (n + 1 simulations) at every trial point, bisection for values only.
  options.line_search_interpolation_type = ceres::BISECTION;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &ceres_problem, &summary);
  // No usable solution (the first evaluation failed): no result, however Ceres fills its cost
  // (-1 when it never evaluated), so that another start wins or the fit fails.
  if (summary.termination_type == ceres::FAILURE)
    return {theta, std::numeric_limits<double>::infinity(),
            static_cast<int>(summary.iterations.size()), summary.message, false};
  return {theta, summary.final_cost, static_cast<int>(summary.iterations.size()),
          summary.message + " (" + std::to_string(summary.num_residual_evaluations) +
              " residual and " + std::to_string(summary.num_jacobian_evaluations) +
              " Jacobian evaluations)",
          summary.termination_type != ceres::NO_CONVERGENCE};
}

// The starting points: the model's own values, then `starts` Latin-hypercube points.
std::vector<std::vector<double>> starting_points(const FitProblem& problem,
                                                 const FitSettings& settings) {
  const std::size_t n = problem.parameters.size();
  const Context context = problem.model->make_context();
  std::vector<std::vector<double>> points(1 + static_cast<std::size_t>(settings.starts),
                                          std::vector<double>(n));
  for (std::size_t j = 0; j < n; ++j) {
    const auto& parameter = problem.parameters[j];
    const double first =
        settings.start.empty() ? context.parameter(parameter.path) : settings.start.at(j);
    points[0][j] = (first - parameter.lower) / (parameter.upper - parameter.lower);
    if (settings.starts == 0 || j < settings.screened_from) {
      for (std::size_t s = 1; s < points.size(); ++s) points[s][j] = points[0][j];
      continue;
    }
    RandomStream stream(settings.seed, "fit start " + parameter.path);
    // A range of more than a decade of a positive parameter is drawn log-uniformly, so that a
    // time scale is tried at every order of magnitude, not mostly near its upper bound.
    const bool decades = parameter.lower > 0.0 && parameter.upper > 10.0 * parameter.lower;
    const auto column =
        decades ? sweep::latin_hypercube_values(parameter.lower, parameter.upper, settings.starts,
                                                sweep::Spacing::logarithmic, stream)
                : sweep::latin_hypercube_values(parameter.lower, parameter.upper, settings.starts,
                                                sweep::Spacing::linear, stream);
    for (std::size_t s = 0; s < column.size(); ++s)
      points[s + 1][j] = (column[s] - parameter.lower) / (parameter.upper - parameter.lower);
  }
  return points;
}

WindowScore score(const std::vector<std::vector<double>>& simulated,
                  const std::vector<std::vector<double>>& measured) {
  WindowScore result;
  for (std::size_t k = 0; k < measured.size(); ++k) {
    const auto& y = measured[k];
    result.samples = y.size();
    const double mean = std::accumulate(y.begin(), y.end(), 0.0) / static_cast<double>(y.size());
    double sse = 0.0, sst = 0.0;
    for (std::size_t i = 0; i < y.size(); ++i) {
      sse += (simulated[k][i] - y[i]) * (simulated[k][i] - y[i]);
      sst += (y[i] - mean) * (y[i] - mean);
    }
    const auto [low, high] = std::minmax_element(y.begin(), y.end());
    const double rmse = std::sqrt(sse / static_cast<double>(y.size()));
    result.rmse.push_back(rmse);
    result.nrmse.push_back(*high > *low ? rmse / (*high - *low) : kNaN);
    result.r2.push_back(sst > 0 ? 1.0 - sse / sst : kNaN);
  }
  return result;
}

// Standard errors and correlations from the weighted Jacobian J (m x n, per SI unit of each
// parameter): covariance s^2 (J^T J)^-1 with s^2 = 2 cost / (m - n), computed through the SVD of
// J with its columns scaled to unit norm, so that the rank test does not depend on units.
void add_statistics(FitResult& result, const Eigen::MatrixXd& jacobian) {
  const auto n = jacobian.cols();
  const auto m = jacobian.rows();
  result.residual_variance = m > n ? 2.0 * result.cost / static_cast<double>(m - n) : kNaN;
  const Eigen::VectorXd norms = jacobian.colwise().norm();
  Eigen::MatrixXd scaled = jacobian;
  for (Eigen::Index j = 0; j < n; ++j) {
    if (norms(j) > 0) scaled.col(j) /= norms(j);
  }
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(scaled, Eigen::ComputeThinV);
  const Eigen::VectorXd sigma = svd.singularValues();
  const double threshold = sigma(0) * 1e-7;
  result.rank = 0;
  Eigen::MatrixXd covariance = Eigen::MatrixXd::Zero(n, n);
  for (Eigen::Index k = 0; k < sigma.size(); ++k) {
    if (sigma(k) > threshold && sigma(k) > 0) {
      ++result.rank;
      covariance += svd.matrixV().col(k) * svd.matrixV().col(k).transpose() / (sigma(k) * sigma(k));
    }
  }
  std::vector<bool> identified(static_cast<std::size_t>(n), true);
  for (Eigen::Index j = 0; j < n; ++j) {
    if (norms(j) == 0) {
      identified[static_cast<std::size_t>(j)] = false;
      result.identifiability.push_back(result.estimates[static_cast<std::size_t>(j)].path +
                                       " does not change the outputs");
    }
  }
  for (Eigen::Index k = result.rank; k < sigma.size(); ++k) {  // the directions without data
    std::string involved;
    for (Eigen::Index j = 0; j < n; ++j) {
      if (std::abs(svd.matrixV()(j, k)) > 0.1 && norms(j) > 0) {
        identified[static_cast<std::size_t>(j)] = false;
        involved +=
            (involved.empty() ? "" : ", ") + result.estimates[static_cast<std::size_t>(j)].path;
      }
    }
    if (!involved.empty()) {
      result.identifiability.push_back("rank " + std::to_string(result.rank) + " of " +
                                       std::to_string(n) + ": the data fix no combination of " +
                                       involved + " (singular value " +
                                       number_text(sigma(k) / sigma(0), 2) + " of the largest)");
    }
  }
  result.correlation = Eigen::MatrixXd::Constant(n, n, kNaN);
  for (Eigen::Index i = 0; i < n; ++i) {
    for (Eigen::Index j = 0; j < n; ++j) {
      if (identified[static_cast<std::size_t>(i)] && identified[static_cast<std::size_t>(j)])
        result.correlation(i, j) =
            covariance(i, j) / std::sqrt(covariance(i, i) * covariance(j, j));
    }
  }
  for (Eigen::Index j = 0; j < n; ++j) {
    auto& estimate = result.estimates[static_cast<std::size_t>(j)];
    estimate.identifiable = identified[static_cast<std::size_t>(j)];
    estimate.standard_error =
        estimate.identifiable ? std::sqrt(result.residual_variance * covariance(j, j)) / norms(j)
                              : kNaN;
    for (Eigen::Index i = 0; i < j; ++i) {
      const double rho = result.correlation(i, j);
      if (std::isfinite(rho) && std::abs(rho) > 0.99) {
        result.identifiability.push_back(result.estimates[static_cast<std::size_t>(i)].path +
                                         " and " + estimate.path + " are correlated (" +
                                         number_text(rho, 5) + ")");
      }
    }
  }
  // What the summary calls not identified, the estimates say too: a parameter in a correlated
  // pair, or whose standard error exceeds its estimate, keeps its (large) standard error but is
  // not identifiable.
  for (Eigen::Index j = 0; j < n; ++j) {
    auto& estimate = result.estimates[static_cast<std::size_t>(j)];
    for (Eigen::Index i = 0; i < n; ++i) {
      const double rho = result.correlation(i, j);
      if (i != j && std::isfinite(rho) && std::abs(rho) > 0.99) estimate.identifiable = false;
    }
    if (estimate.identifiable && estimate.standard_error > std::abs(estimate.value)) {
      estimate.identifiable = false;
      result.identifiability.push_back(estimate.path + ": its standard error " +
                                       number_text(estimate.standard_error, 3) +
                                       " exceeds its estimate " + number_text(estimate.value, 3));
    }
  }
}

// Whether the fit uses forward sensitivities, and what the report says of its gradient.
std::pair<bool, std::string> choose_gradient(const FitProblem& problem, Gradient gradient) {
  const std::string unavailable = sensitivities_unavailable(problem);
  if (gradient == Gradient::differences) return {false, "finite differences (as asked)"};
  if (unavailable.empty()) return {true, "forward sensitivities (CVODES)"};
  if (gradient == Gradient::sensitivities)
    throw std::invalid_argument("forward sensitivities are not available: " + unavailable);
  return {false, "finite differences (no forward sensitivities: " + unavailable + ")"};
}

// A problem whose windows hold too few samples is the caller's mistake (load_fit refuses it at
// its key): std::invalid_argument, never a score of no samples.
void check_windows(const FitProblem& problem) {
  std::string problem_text =
      window_samples_problem(*problem.data, problem.identification, 1, "the identification window");
  if (problem_text.empty() && problem.validation.to > problem.validation.from)
    problem_text =
        window_samples_problem(*problem.data, problem.validation, 1, "the validation window");
  if (!problem_text.empty()) throw std::invalid_argument(problem_text);
}

}  // namespace

WindowScore score_window(const FitProblem& problem, const std::vector<double>& values,
                         const TimeWindow& window) {
  return score(simulate_outputs(problem, values, window), measured_outputs(problem, window));
}

FitResult fit_model(const FitProblem& problem, const FitSettings& settings) {
  if (settings.max_iterations < 0 || settings.starts < 0 || settings.refine < 0)
    throw std::invalid_argument("fit settings: max_iterations " +
                                std::to_string(settings.max_iterations) + ", starts " +
                                std::to_string(settings.starts) + ", refine " +
                                std::to_string(settings.refine) + ": none may be negative");
  check_windows(problem);
  const auto [sensitivities, gradient] = choose_gradient(problem, settings.gradient);
  const Residuals residuals(problem);
  const auto points = starting_points(problem, settings);
  std::vector<double> costs(points.size());
  std::vector<std::string> labels(points.size(), "start");
  run_in_parallel(labels, settings.threads, [&](std::size_t s) {
    costs[s] = residuals.cost(physical(problem, points[s].data()));
  });
  const std::size_t first_refined = settings.drawn_starts_only && points.size() > 1 ? 1 : 0;
  std::vector<std::size_t> order(points.size() - first_refined);
  std::iota(order.begin(), order.end(), first_refined);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return costs[a] < costs[b]; });
  Refined best;
  best.cost = std::numeric_limits<double>::infinity();
  std::size_t best_start = 0;
  int iterations = 0;
  const auto refinements =
      std::min<std::size_t>(order.size(), static_cast<std::size_t>(std::max(1, settings.refine)));
  for (std::size_t r = 0; r < refinements; ++r) {
    if (!std::isfinite(costs[order[r]])) break;
    Refined candidate = refine(problem, residuals, settings, sensitivities, points[order[r]]);
    iterations += candidate.iterations;
    if (candidate.cost < best.cost) {
      best = std::move(candidate);
      best_start = order[r];
    }
  }
  if (!std::isfinite(best.cost)) {
    throw FitFailure("the model could not be simulated at any starting point; the first failure: " +
                     residuals.first_failure());
  }

  FitResult result;
  result.cost = best.cost;
  result.start_cost = costs[0];
  result.refined_start = best_start;
  result.iterations = iterations;
  result.termination = best.termination;
  result.converged = best.converged;
  result.gradient = gradient;
  const std::vector<double> values = physical(problem, best.theta.data());
  const Context context = problem.model->make_context();
  for (std::size_t j = 0; j < problem.parameters.size(); ++j) {
    const auto& parameter = problem.parameters[j];
    const double initial =
        settings.start.empty() ? context.parameter(parameter.path) : settings.start[j];
    result.estimates.push_back({parameter.path, parameter.unit, initial, values[j], kNaN, true,
                                bound_reached(best.theta[j])});
  }
  // The Jacobian at the estimate, per SI unit of each parameter.
  const SimulationCost cost(problem, residuals, settings, sensitivities);
  const std::size_t m = residuals.count(), n = values.size();
  std::vector<double> r(m), jacobian_values(m * n);
  double* jacobian_pointer = jacobian_values.data();
  const double* theta = best.theta.data();
  if (!cost.Evaluate(&theta, r.data(), &jacobian_pointer)) {
    throw FitFailure("the model could not be simulated around the estimate: " +
                     residuals.first_failure());
  }
  Eigen::MatrixXd jacobian(static_cast<Eigen::Index>(m), static_cast<Eigen::Index>(n));
  for (std::size_t i = 0; i < m; ++i) {
    for (std::size_t j = 0; j < n; ++j) {
      const auto& parameter = problem.parameters[j];
      jacobian(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) =
          jacobian_values[i * n + j] / (parameter.upper - parameter.lower);
    }
  }
  add_statistics(result, jacobian);
  result.identification = score_window(problem, values, problem.identification);
  if (problem.validation.to > problem.validation.from)
    result.validation = score_window(problem, values, problem.validation);
  result.simulations = residuals.simulations();
  return result;
}

}  // namespace tcpmsim::fit
