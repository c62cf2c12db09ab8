#include "sim/integrator.h"

#include "sim/serial_vector_kernels.h"
#include "sim/time_grid.h"
#include "sim/value_check.h"

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_band.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_band.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>
#include <sunnonlinsol/sunnonlinsol_fixedpoint.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>

namespace tcpmsim {

// All CVODE handles, released in reverse order of creation.
struct detail::CvodeHandles {
  SUNContext sundials = nullptr;
  N_Vector state = nullptr;
  N_Vector scratch = nullptr;
  SUNMatrix matrix = nullptr;
  SUNLinearSolver linear_solver = nullptr;
  SUNNonlinearSolver nonlinear_solver = nullptr;
  void* memory = nullptr;

  // Bookkeeping the callbacks need.
  const System* system = nullptr;
  Context* context = nullptr;
  // Piecewise signals are sampled inside [segment_start, segment_end], a few rounding errors
  // inside the segment, so each segment sees one piece of every signal, whatever the rounding
  // of times composed from shifted pieces.
  double segment_start = 0.0;
  double segment_end = 0.0;
  double signal_time(double t) const { return std::clamp(t, segment_start, segment_end); }
  std::string last_message;
  std::string rhs_problem;
  SparsityPattern pattern;
  std::vector<std::vector<int>> column_groups;
  std::vector<double> perturbed;
  std::vector<double> perturbed_derivatives;
  std::vector<int> event_flags;
  std::vector<double> configured_tolerances;
  std::vector<double> adapted_tolerances;
  std::vector<double> relative_tolerances;  // per state; the configured rtol unless adapted

  ~CvodeHandles() {
    if (memory) CVodeFree(&memory);
    if (nonlinear_solver) SUNNonlinSolFree(nonlinear_solver);
    if (linear_solver) SUNLinSolFree(linear_solver);
    if (matrix) SUNMatDestroy(matrix);
    if (scratch) N_VDestroy(scratch);
    if (state) N_VDestroy(state);
    if (sundials) SUNContext_Free(&sundials);
  }
};

namespace {

// Output times t0 + k * interval, then t_end if that is off the grid.
class OutputGrid {
 public:
  OutputGrid(double t0, double t_end, double interval)
      : t0_(t0), t_end_(t_end), interval_(interval) {
    const auto last_on_grid =
        static_cast<long>(std::floor((t_end - t0) / interval * (1.0 + 1e-12)));
    const double last = t0 + static_cast<double>(last_on_grid) * interval;
    const bool end_on_grid = std::abs(last - t_end) <= 1e-9 * std::max(1.0, std::abs(t_end));
    count_ = last_on_grid + (end_on_grid ? 1 : 2);
  }
  bool done() const { return index_ >= count_; }
  void advance() { ++index_; }
  double time() const {
    return index_ + 1 == count_ ? t_end_ : t0_ + static_cast<double>(index_) * interval_;
  }

 private:
  double t0_, t_end_, interval_;
  long count_ = 0, index_ = 0;
};

constexpr int kUnrecoverable = -1;
constexpr int kRecoverable = 1;

detail::CvodeHandles& cvode_of(void* user_data) {
  return *static_cast<detail::CvodeHandles*>(user_data);
}

int right_hand_side(realtype t, N_Vector y, N_Vector ydot, void* user_data) {
  auto& cv = cvode_of(user_data);
  const double* state = N_VGetArrayPointer(y);
  double* derivatives = N_VGetArrayPointer(ydot);
  const int size = cv.system->state_size();
  for (int i = 0; i < size; ++i) {
    if (!std::isfinite(state[i])) {
      cv.rhs_problem = "state " + cv.system->states()[static_cast<std::size_t>(i)].name +
                       " is not finite at t = " + number_text(t) + " s";
      return kUnrecoverable;
    }
  }
  cv.system->evaluate_derivatives(*cv.context, t, cv.signal_time(t), state, derivatives);
  for (int i = 0; i < size; ++i) {
    if (!std::isfinite(derivatives[i])) {
      const auto& info = cv.system->states()[static_cast<std::size_t>(i)];
      cv.rhs_problem = "the derivative of " + info.name + " (component " + info.owner->group() +
                       "/" + info.owner->kind() + ") is not finite at t = " + number_text(t) + " s";
      return kRecoverable;
    }
  }
  return 0;
}

// CVODE's own vector-tolerance weights, 1 / (rtol |y_i| + atol_i), over tolerances that the
// components may adapt between steps (CVodeSVtolerances cannot be called mid-run in 6.4).
int error_weights(N_Vector y, N_Vector weights, void* user_data) {
  auto& cv = cvode_of(user_data);
  const double* state = N_VGetArrayPointer(y);
  double* weight = N_VGetArrayPointer(weights);
  const double* absolute = cv.adapted_tolerances.data();
  const double* relative = cv.relative_tolerances.data();
  for (std::size_t i = 0; i < cv.adapted_tolerances.size(); ++i) {
    const double scale = (relative[i] * std::abs(state[i])) + absolute[i];
    if (!(scale > 0.0)) return -1;
    weight[i] = 1.0 / scale;
  }
  return 0;
}

int event_functions(realtype t, N_Vector y, realtype* values, void* user_data) {
  auto& cv = cvode_of(user_data);
  cv.system->evaluate_events(*cv.context, t, cv.signal_time(t), N_VGetArrayPointer(y), values);
  return 0;
}

// CVODE zeroes the whole sparse matrix, structure included, before each Jacobian call.
void write_structure(const SparsityPattern& pattern, SUNMatrix matrix) {
  sunindextype* column_start = SUNSparseMatrix_IndexPointers(matrix);
  sunindextype* row_index = SUNSparseMatrix_IndexValues(matrix);
  sunindextype entry = 0;
  for (int column = 0; column < pattern.size; ++column) {
    column_start[column] = entry;
    for (int row : pattern.rows_of_column[static_cast<std::size_t>(column)]) {
      row_index[entry++] = row;
    }
  }
  column_start[pattern.size] = entry;
}

// Column-grouped finite differences into the sparse (CSC) matrix KLU factors.
int sparse_jacobian(realtype t, N_Vector y, N_Vector fy, SUNMatrix jacobian, void* user_data,
                    N_Vector, N_Vector, N_Vector) {
  auto& cv = cvode_of(user_data);
  const double* state = N_VGetArrayPointer(y);
  const double* base = N_VGetArrayPointer(fy);
  const double* absolute = cv.adapted_tolerances.data();
  const double* relative = cv.relative_tolerances.data();
  write_structure(cv.pattern, jacobian);
  double* data = SUNSparseMatrix_Data(jacobian);
  const sunindextype* column_start = SUNSparseMatrix_IndexPointers(jacobian);
  const double root_epsilon = std::sqrt(std::numeric_limits<double>::epsilon());
  std::copy(state, state + cv.pattern.size, cv.perturbed.begin());
  for (const auto& group : cv.column_groups) {
    for (int column : group) {
      const double scale = relative[column] * std::abs(state[column]) + absolute[column];
      cv.perturbed[static_cast<std::size_t>(column)] +=
          root_epsilon * std::max(std::abs(state[column]), scale);
    }
    cv.system->evaluate_derivatives(*cv.context, t, cv.signal_time(t), cv.perturbed.data(),
                                    cv.perturbed_derivatives.data());
    for (int column : group) {
      const auto c = static_cast<std::size_t>(column);
      const double increment = cv.perturbed[c] - state[column];
      sunindextype entry = column_start[column];
      for (int row : cv.pattern.rows_of_column[c]) {
        data[entry++] =
            (cv.perturbed_derivatives[static_cast<std::size_t>(row)] - base[row]) / increment;
      }
      cv.perturbed[c] = state[column];
    }
  }
  return 0;
}

void capture_error(int, const char* module, const char* function, char* message, void* user_data) {
  cvode_of(user_data).last_message = std::string(module) + "/" + function + ": " + message;
}

void check(int flag, const char* call) {
  if (flag < 0) {
    throw std::runtime_error(std::string("CVODE setup failed in ") + call + ": " +
                             CVodeGetReturnFlagName(flag));
  }
}

}  // namespace

Integrator::Integrator(const System& system, Context& context, SolverSettings settings)
    : cvode_(std::make_unique<detail::CvodeHandles>()),
      system_(system),
      context_(context),
      settings_(std::move(settings)) {
  const int size = system_.state_size();
  if (size == 0) throw std::logic_error("the system has no continuous states to integrate");
  if (&context_.system() != &system_)
    throw std::logic_error("the context belongs to another system");
  auto& cv = *cvode_;
  cv.system = &system_;
  cv.context = &context_;
  check(SUNContext_Create(nullptr, &cv.sundials), "SUNContext_Create");
  cv.state = N_VMake_Serial(size, context_.state().data(), cv.sundials);
  install_optimised_serial_kernels(cv.state);  // before cloning: the clones inherit them
  cv.scratch = N_VClone(cv.state);
  for (int i = 0; i < size; ++i) {
    const auto index = static_cast<std::size_t>(i);
    cv.configured_tolerances.push_back(settings_.absolute_tolerances.empty()
                                           ? system_.states()[index].absolute_tolerance
                                           : settings_.absolute_tolerances.at(index));
  }
  cv.adapted_tolerances = cv.configured_tolerances;
  cv.relative_tolerances.assign(static_cast<std::size_t>(size), settings_.relative_tolerance);
  cv.memory =
      CVodeCreate(settings_.method == IntegrationMethod::adams ? CV_ADAMS : CV_BDF, cv.sundials);
  if (!cv.memory) throw std::runtime_error("CVodeCreate failed");
}

Integrator::~Integrator() = default;

void Integrator::attach_linear_solver() {
  auto& cv = *cvode_;
  const int size = system_.state_size();
  switch (settings_.linear_solver) {
    case LinearSolverKind::dense:
      cv.matrix = SUNDenseMatrix(size, size, cv.sundials);
      cv.linear_solver = SUNLinSol_Dense(cv.state, cv.matrix, cv.sundials);
      break;
    case LinearSolverKind::band: {
      const SparsityPattern pattern = system_.jacobian_pattern();
      cv.matrix =
          SUNBandMatrix(size, pattern.upper_bandwidth(), pattern.lower_bandwidth(), cv.sundials);
      cv.linear_solver = SUNLinSol_Band(cv.state, cv.matrix, cv.sundials);
      break;
    }
    case LinearSolverKind::klu: {
      cv.pattern = system_.jacobian_pattern();
      cv.column_groups = cv.pattern.column_groups();
      cv.perturbed.assign(static_cast<std::size_t>(size), 0.0);
      cv.perturbed_derivatives.assign(static_cast<std::size_t>(size), 0.0);
      cv.matrix = SUNSparseMatrix(size, size, cv.pattern.non_zeros(), CSC_MAT, cv.sundials);
      write_structure(cv.pattern, cv.matrix);
      cv.linear_solver = SUNLinSol_KLU(cv.state, cv.matrix, cv.sundials);
      break;
    }
  }
  if (!cv.matrix || !cv.linear_solver)
    throw std::runtime_error("could not create the linear solver");
  check(CVodeSetLinearSolver(cv.memory, cv.linear_solver, cv.matrix), "CVodeSetLinearSolver");
  if (settings_.linear_solver == LinearSolverKind::klu) {
    check(CVodeSetJacFn(cv.memory, sparse_jacobian), "CVodeSetJacFn");
  }
}

void Integrator::accumulate_statistics() {
  auto& cv = *cvode_;
  auto add = [](auto getter, void* memory, long& total) {
    long value = 0;
    getter(memory, &value);
    total += value;
  };
  add(CVodeGetNumSteps, cv.memory, statistics_.steps);
  add(CVodeGetNumRhsEvals, cv.memory, statistics_.rhs_evaluations);
  add(CVodeGetNumLinSolvSetups, cv.memory, statistics_.linear_solver_setups);
  add(CVodeGetNumErrTestFails, cv.memory, statistics_.error_test_failures);
  add(CVodeGetNumNonlinSolvIters, cv.memory, statistics_.nonlinear_iterations);
  add(CVodeGetNumNonlinSolvConvFails, cv.memory, statistics_.nonlinear_convergence_failures);
  if (settings_.method == IntegrationMethod::bdf) {
    add(CVodeGetNumJacEvals, cv.memory, statistics_.jacobian_evaluations);
    add(CVodeGetNumLinRhsEvals, cv.memory, statistics_.rhs_evaluations_for_jacobian);
  }
}

SolverFailure Integrator::failure(const std::string& headline) {
  auto& cv = *cvode_;
  const int size = system_.state_size();
  double now = 0.0;
  CVodeGetCurrentTime(cv.memory, &now);
  accumulate_statistics();
  std::ostringstream message;
  message << headline << " at t = " << now << " s";
  if (!cv.rhs_problem.empty()) message << ": " << cv.rhs_problem;
  if (!cv.last_message.empty()) message << "\n  CVODE said: " << cv.last_message;
  // Rank the states by weighted local error, |e_i| * w_i, the quantity CVODE's test uses.
  N_Vector weights = N_VClone(cv.scratch);
  N_Vector errors = N_VClone(cv.scratch);
  CVodeGetErrWeights(cv.memory, weights);
  CVodeGetEstLocalErrors(cv.memory, errors);
  std::vector<std::pair<double, int>> ranked;
  for (int i = 0; i < size; ++i) {
    ranked.emplace_back(std::abs(N_VGetArrayPointer(errors)[i] * N_VGetArrayPointer(weights)[i]),
                        i);
  }
  N_VDestroy(weights);
  N_VDestroy(errors);
  std::sort(ranked.begin(), ranked.end(),
            [](const auto& a, const auto& b) { return a.first > b.first; });
  const double* state = N_VGetArrayPointer(cv.state);
  message << "\n  state entries with the largest weighted local error:";
  for (std::size_t k = 0; k < std::min<std::size_t>(3, ranked.size()); ++k) {
    const auto& info = system_.states()[static_cast<std::size_t>(ranked[k].second)];
    message << "\n    " << info.name << " = " << state[ranked[k].second] << " " << info.unit
            << " (weighted error " << ranked[k].first << ", component " << info.owner->group()
            << "/" << info.owner->kind() << ")";
  }
  return SolverFailure(message.str(), now, statistics_);
}

void Integrator::refresh_tolerances() {
  auto& cv = *cvode_;
  std::copy(cv.configured_tolerances.begin(), cv.configured_tolerances.end(),
            cv.adapted_tolerances.begin());
  std::fill(cv.relative_tolerances.begin(), cv.relative_tolerances.end(),
            settings_.relative_tolerance);
  system_.adapt_tolerances(context_, cv.adapted_tolerances.data(), cv.relative_tolerances.data());
}

void Integrator::start_segment(double start, bool first) {
  auto& cv = *cvode_;
  if (first) {
    check(CVodeInit(cv.memory, right_hand_side, start, cv.state), "CVodeInit");
    check(CVodeSetUserData(cv.memory, cvode_.get()), "CVodeSetUserData");
    check(CVodeSetErrHandlerFn(cv.memory, capture_error, cvode_.get()), "CVodeSetErrHandlerFn");
    check(CVodeWFtolerances(cv.memory, error_weights), "CVodeWFtolerances");
    if (settings_.method == IntegrationMethod::adams) {
      cv.nonlinear_solver = SUNNonlinSol_FixedPoint(cv.state, 0, cv.sundials);
      check(CVodeSetNonlinearSolver(cv.memory, cv.nonlinear_solver), "CVodeSetNonlinearSolver");
    } else {
      attach_linear_solver();
    }
    check(CVodeSetMaxNumSteps(cv.memory, -1), "CVodeSetMaxNumSteps");
    if (settings_.max_step > 0)
      check(CVodeSetMaxStep(cv.memory, settings_.max_step), "CVodeSetMaxStep");
    if (system_.event_count() > 0) {
      check(CVodeRootInit(cv.memory, system_.event_count(), event_functions), "CVodeRootInit");
      std::vector<int> directions = system_.event_directions();
      check(CVodeSetRootDirection(cv.memory, directions.data()), "CVodeSetRootDirection");
      cv.event_flags.assign(directions.size(), 0);
    }
  } else {
    accumulate_statistics();  // CVodeReInit zeroes CVODE's counters
    check(CVodeReInit(cv.memory, start, cv.state), "CVodeReInit");
  }
  if (settings_.initial_step > 0)
    check(CVodeSetInitStep(cv.memory, settings_.initial_step), "CVodeSetInitStep");
  refresh_tolerances();
}

SolverStatistics Integrator::run(double t0, double t_end, OutputTimes output, OutputSink& sink,
                                 const Progress& progress) {
  auto& cv = *cvode_;
  double* state = N_VGetArrayPointer(cv.state);
  system_.initialize(context_, t0, state);
  system_.at_breakpoint(context_, t0, t0, state);  // sampled components take their first sample
  statistics_ = {};
  OutputGrid grid(std::max(t0, output.start), t_end, output.interval);
  long steps_taken = 0;
  int collapsed_steps = 0;

  double t = t0;
  while (t < t_end) {
    // Breakpoints closer than a few rounding errors are one event; a signal composed from
    // shifted pieces may report an instant that is t itself after rounding.
    const double margin = time_margin(t);
    double stop = system_.next_breakpoint_after(context_, t);
    while (stop <= t + 2.0 * margin)
      stop = system_.next_breakpoint_after(context_, std::max(stop, t + 2.0 * margin));
    stop = std::min(stop, t_end);
    const bool last_segment = stop >= t_end;
    start_segment(t, t == t0);
    check(CVodeSetStopTime(cv.memory, stop), "CVodeSetStopTime");
    cv.segment_start = t + margin;
    cv.segment_end = stop - time_margin(stop);
    ++statistics_.segments;
    collapsed_steps = 0;  // a restart's first steps are small by design
    double reached = t;
    while (reached < stop) {
      cv.rhs_problem.clear();
      const int flag = CVode(cv.memory, stop, cv.state, &reached, CV_ONE_STEP);
      if (flag < 0) throw failure(std::string("CVODE failed with ") + CVodeGetReturnFlagName(flag));
      if (flag == CV_TSTOP_RETURN) reached = stop;
      if (flag == CV_ROOT_RETURN) {
        ++statistics_.events;
        check(CVodeGetRootInfo(cv.memory, cv.event_flags.data()), "CVodeGetRootInfo");
        system_.at_events(context_, reached, cv.signal_time(reached), state, cv.event_flags.data());
        refresh_tolerances();
      }
      if (++steps_taken > settings_.max_steps) {
        throw failure("more than " + std::to_string(settings_.max_steps) +
                      " solver steps (raise solver.max_steps if this is expected)");
      }
      // A step size shrinking to rounding level without an error means the solution is
      // running into a singularity it can neither pass nor reject: stop and say where.
      double last_step = 0.0;
      CVodeGetLastStep(cv.memory, &last_step);
      collapsed_steps = last_step < 1e3 * time_margin(reached) ? collapsed_steps + 1 : 0;
      if (collapsed_steps > 100) {
        throw failure("CVODE stalled (the step size collapsed to " + number_text(last_step) +
                      " s)");
      }
      // Interpolate every output time this step covered; a time equal to a breakpoint belongs
      // to the next segment (outputs are right-continuous), except the final time.
      for (; !grid.done(); grid.advance()) {
        const double when = grid.time();
        if (when > reached || (when >= stop && !last_segment)) break;
        check(CVodeGetDky(cv.memory, when, 0, cv.scratch), "CVodeGetDky");
        system_.evaluate_outputs(context_, when, cv.signal_time(when),
                                 N_VGetArrayPointer(cv.scratch));
        sink.record(when, context_.signals());
        ++statistics_.output_samples;
      }
      if (progress) progress(reached, steps_taken);
    }
    t = stop;
    if (t < t_end) system_.at_breakpoint(context_, t, t - time_margin(t), state);
  }
  accumulate_statistics();
  return statistics_;
}

}  // namespace tcpmsim
