#include "sim/integrator.h"

#include "sim/block_preconditioner.h"
#include "sim/forward_sensitivity.h"
#include "sim/klu_solver.h"
#include "sim/output_grid.h"
#include "sim/serial_vector_kernels.h"
#include "sim/time_grid.h"
#include "sim/value_check.h"

#include <cvodes/cvodes.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_band.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunlinsol/sunlinsol_spgmr.h>
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
  SUNMatrix matrix = nullptr;  // the Newton matrix's; with GMRES, the Jacobian for J v
  SUNLinearSolver linear_solver = nullptr;
  std::unique_ptr<BlockPreconditioner> preconditioner;  // GMRES's
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
  // Dense rows read through a fan-in (a load on every member), by the chain rule.
  struct ChainRule {
    // An entry of the rule's row: its column, and its place in that column of the pattern.
    struct Entry {
      int source;  // through which source it moves the row (-1: directly)
      int column;
      std::size_t place;
    };
    FanInRow row;
    std::vector<double> sensitivity;          // d f_row / d source, at the Jacobian's state
    std::vector<double> base_sources;         // the sources there
    std::vector<std::vector<Entry>> entries;  // per column group: the row's entries it moves
  };
  std::vector<ChainRule> chain_rules;
  std::vector<char> chain_row;  // per state: its row is a chain rule's
  std::vector<double> base_derivatives, scratch_derivatives, increments;
  bool warm_restarts = false;
  std::vector<double> carried_jacobian;  // the pattern's entries, column by column
  bool offer_carried_jacobian = false;
  long carried_jacobians = 0;         // handed back since the last count: CVODE counts them as new
  long preconditioner_jacobians = 0;  // asked for by the preconditioner since the last count
  long jacobian_rhs_evaluations = 0;  // by the grouped differences, since the last count
  long steps = 0;                     // over the whole run, across restarts
  long jacobian_step = -1;    // `steps` when the carried Jacobian was computed; -1: none yet
  double restart_step = 0.0;  // the first step a warm restart tries (0: CVODE's estimate)
  std::vector<int> event_flags;
  std::vector<double> configured_tolerances;
  std::vector<double> adapted_tolerances;
  std::vector<double> relative_tolerances;  // per state; the configured rtol unless adapted
  // Forward sensitivities, when a run tracks them: s_j (CVODES' state) and s_j at an output time.
  ForwardSensitivities* sensitivities = nullptr;
  int sensitivity_count = 0;
  N_Vector* sensitivity_state = nullptr;
  N_Vector* sensitivity_output = nullptr;
  std::vector<double*> sensitivity_pointers;

  ~CvodeHandles() {
    if (memory) CVodeFree(&memory);
    if (sensitivity_output) N_VDestroyVectorArray(sensitivity_output, sensitivity_count);
    if (sensitivity_state) N_VDestroyVectorArray(sensitivity_state, sensitivity_count);
    if (nonlinear_solver) SUNNonlinSolFree(nonlinear_solver);
    if (linear_solver) SUNLinSolFree(linear_solver);
    preconditioner.reset();
    if (matrix) SUNMatDestroy(matrix);
    if (scratch) N_VDestroy(scratch);
    if (state) N_VDestroy(state);
    if (sundials) SUNContext_Free(&sundials);
  }
};

namespace detail {

// Output times t0 + k * interval, then t_end if that is off the grid.
class OutputGrid {
 public:
  OutputGrid(double t0, double t_end, double interval)
      : t0_(t0),
        t_end_(t_end),
        interval_(interval),
        count_(static_cast<long>(output_sample_count(t0, t_end, interval))) {}
  bool done() const { return index_ >= count_; }
  void advance() { ++index_; }
  double time() const {
    return index_ + 1 == count_ ? t_end_ : t0_ + static_cast<double>(index_) * interval_;
  }

 private:
  double t0_, t_end_, interval_;
  long count_ = 0;
  long index_ = 0;
};

// Where a run stands between calls of Integrator::advance.
struct Course {
  double t0, t_end, t;
  OutputGrid grid;
  OutputSink* sink;
  bool hold_instants;         // each advance leaves its end instant half taken
  bool instant_held = false;  // the instant at t waits for its controllers and actuators
  long steps_taken = 0;
  bool ended = false;  // the statistics of the whole run are counted
};

}  // namespace detail

namespace {

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

// s_j' for every tracked parameter j (ForwardSensitivities::derivatives).
int sensitivity_right_hand_side(int count, realtype t, N_Vector y, N_Vector, N_Vector* sensitivity,
                                N_Vector* derivative, void* user_data, N_Vector, N_Vector) {
  auto& cv = cvode_of(user_data);
  const double* state = N_VGetArrayPointer(y);
  const auto size = static_cast<std::size_t>(cv.system->state_size());
  for (int j = 0; j < count; ++j) {
    double* result = N_VGetArrayPointer(derivative[j]);
    cv.sensitivities->derivatives(j, t, cv.signal_time(t), state,
                                  N_VGetArrayPointer(sensitivity[j]), result);
    if (!std::all_of(result, result + size, [](double value) { return std::isfinite(value); })) {
      cv.rhs_problem = "a sensitivity's derivative is not finite at t = " + number_text(t) + " s";
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

// Entry k of a column of the pattern (row pattern.rows_of_column[column][k]) in whichever
// matrix CVODE hands over: sparse (the pattern's own CSC layout), dense or band.
class PatternSlots {
 public:
  PatternSlots(const SparsityPattern& pattern, SUNMatrix matrix)
      : pattern_(pattern), matrix_(matrix), id_(SUNMatGetID(matrix)) {
    if (id_ == SUNMATRIX_SPARSE) {
      write_structure(pattern, matrix);
      data_ = SUNSparseMatrix_Data(matrix);
      column_start_ = SUNSparseMatrix_IndexPointers(matrix);
    }
  }
  double& at(int column, std::size_t k) const {
    const int row = pattern_.rows_of_column[static_cast<std::size_t>(column)][k];
    switch (id_) {
      case SUNMATRIX_SPARSE:
        return data_[column_start_[column] + static_cast<sunindextype>(k)];
      case SUNMATRIX_BAND:
        return SM_ELEMENT_B(matrix_, row, column);
      default:
        return SM_ELEMENT_D(matrix_, row, column);
    }
  }

 private:
  const SparsityPattern& pattern_;
  SUNMatrix matrix_;
  SUNMatrix_ID id_;
  double* data_ = nullptr;
  const sunindextype* column_start_ = nullptr;
};

// The Jacobian by finite differences over groups of structurally orthogonal columns
// (Curtis-Powell-Reid), into any matrix kind. With warm restarts it keeps the values, and the
// first call of a segment (CVODE asks at every restart) gets the last Jacobian back. CVODE then
// takes it for current: if the Newton iteration fails with it, the step is cut (by 4) and
// retried, and that retry (CV_FAIL_OTHER) gets a fresh Jacobian. One is carried into a new
// segment only while fewer than CVODE's reuse limit of steps (msbj = 51) have passed since it
// was computed; inside the segment CVODE counts afresh, so it may serve up to 51 more.
constexpr long kJacobianReuseSteps = 51;

// The chain rules' derivatives and sources at the Jacobian's state, and their sensitivities.
void prepare_chain_rules(detail::CvodeHandles& cv, double t, const double* state) {
  cv.system->evaluate_derivatives(*cv.context, t, cv.signal_time(t), state,
                                  cv.base_derivatives.data());
  const double root_epsilon = std::sqrt(std::numeric_limits<double>::epsilon());
  const auto& signals = cv.context->signals();
  for (auto& rule : cv.chain_rules) {
    for (std::size_t k = 0; k < rule.row.sources.size(); ++k) {
      const double source = signals[static_cast<std::size_t>(rule.row.sources[k])];
      rule.base_sources[k] = source;
      rule.sensitivity[k] = cv.system->row_sensitivity(
          *cv.context, t, cv.signal_time(t), state, rule.row, rule.row.sources[k],
          root_epsilon * std::max(std::abs(source), 1.0), cv.scratch_derivatives.data());
    }
  }
}

// Group g's contribution to a chain rule's row: through each source that one of the group's
// columns moved, sensitivity times the source's change; the rest of the row's change is its own
// (direct) column's, which the colouring puts in the group after the sources' entries.
void add_chain_entries(detail::CvodeHandles& cv, const detail::CvodeHandles::ChainRule& rule,
                       std::size_t g, const PatternSlots& slots) {
  const auto& signals = cv.context->signals();
  const auto r = static_cast<std::size_t>(rule.row.row);
  double remainder = cv.perturbed_derivatives[r] - cv.base_derivatives[r];
  for (const auto& entry : rule.entries[g]) {
    double change = remainder;  // what the sources left, for the direct entry
    if (entry.source >= 0) {
      const auto source = static_cast<std::size_t>(entry.source);
      change =
          rule.sensitivity[source] *
          (signals[static_cast<std::size_t>(rule.row.sources[source])] - rule.base_sources[source]);
      remainder -= change;
    }
    slots.at(entry.column, entry.place) +=
        change / cv.increments[static_cast<std::size_t>(entry.column)];
  }
}

enum class CarryDirection { into_matrix, from_matrix };

// The carried Jacobian holds the pattern's entries column by column.
void copy_carried(detail::CvodeHandles& cv, const PatternSlots& slots, CarryDirection direction) {
  cv.carried_jacobian.resize(static_cast<std::size_t>(cv.pattern.non_zeros()));
  auto value = cv.carried_jacobian.begin();
  for (int column = 0; column < cv.pattern.size; ++column) {
    const std::size_t rows = cv.pattern.rows_of_column[static_cast<std::size_t>(column)].size();
    for (std::size_t k = 0; k < rows; ++k, ++value) {
      if (direction == CarryDirection::into_matrix)
        slots.at(column, k) = *value;
      else
        *value = slots.at(column, k);
    }
  }
}

int grouped_jacobian(realtype t, N_Vector y, N_Vector fy, SUNMatrix jacobian, void* user_data,
                     N_Vector, N_Vector, N_Vector) {
  auto& cv = cvode_of(user_data);
  const PatternSlots slots(cv.pattern, jacobian);
  long convergence_failures = 0;
  CVodeGetNumNonlinSolvConvFails(cv.memory, &convergence_failures);
  // Offered until the segment's first step or Newton's first failure: a retry after an error
  // test failure (a smaller first step) keeps it, a convergence failure gets a fresh one.
  cv.offer_carried_jacobian = cv.offer_carried_jacobian && convergence_failures == 0;
  const bool carry = cv.offer_carried_jacobian && cv.jacobian_step >= 0 &&
                     cv.steps - cv.jacobian_step < kJacobianReuseSteps;
  if (carry) {
    ++cv.carried_jacobians;
    copy_carried(cv, slots, CarryDirection::into_matrix);
    return 0;
  }
  const double* state = N_VGetArrayPointer(y);
  const double* base = N_VGetArrayPointer(fy);
  const double* absolute = cv.adapted_tolerances.data();
  const double* relative = cv.relative_tolerances.data();
  const double root_epsilon = std::sqrt(std::numeric_limits<double>::epsilon());
  if (!cv.chain_rules.empty()) prepare_chain_rules(cv, t, state);
  cv.jacobian_rhs_evaluations +=
      static_cast<long>(cv.column_groups.size()) + (cv.chain_rules.empty() ? 0 : 1);
  std::copy(state, state + cv.pattern.size, cv.perturbed.begin());
  for (std::size_t g = 0; g < cv.column_groups.size(); ++g) {
    const auto& group = cv.column_groups[g];
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
      const auto& rows = cv.pattern.rows_of_column[c];
      for (std::size_t k = 0; k < rows.size(); ++k) {
        const auto row = static_cast<std::size_t>(rows[k]);
        if (!cv.chain_row.empty() && cv.chain_row[row]) continue;  // below
        slots.at(column, k) = (cv.perturbed_derivatives[row] - base[row]) / increment;
      }
      if (!cv.chain_rules.empty()) cv.increments[c] = increment;
      cv.perturbed[c] = state[column];
    }
    for (const auto& rule : cv.chain_rules) add_chain_entries(cv, rule, g, slots);
  }
  if (cv.warm_restarts) {
    cv.jacobian_step = cv.steps;
    copy_carried(cv, slots, CarryDirection::from_matrix);
  }
  return 0;
}

// A fan-in of this many sources makes a row the chain rule's (fewer cost little as they are).
constexpr int kChainFromSources = 16;

// Column groups for the finite differences. Rows read through a wide fan-in (chain rules) are
// left out of the colouring; in their place come pseudo-rows, one for each source (its states)
// and one for the row's direct states, so that each group moves at most one column per source
// and one of the row's own: then the source changes apportion the row's change.
std::vector<std::vector<int>> colour_columns(detail::CvodeHandles& cv, std::vector<FanInRow> rows) {
  if (rows.empty()) return cv.pattern.column_groups();
  const auto size = static_cast<std::size_t>(cv.pattern.size);
  cv.chain_row.assign(size, 0);
  for (const auto& row : rows) cv.chain_row[static_cast<std::size_t>(row.row)] = 1;
  SparsityPattern colouring = cv.pattern;
  for (auto& column_rows : colouring.rows_of_column) {
    std::erase_if(column_rows,
                  [&](int row) { return cv.chain_row[static_cast<std::size_t>(row)] != 0; });
  }
  int pseudo_row = cv.pattern.size;
  const auto add_pseudo_row = [&](const std::vector<int>& columns) {
    for (int column : columns)
      colouring.rows_of_column[static_cast<std::size_t>(column)].push_back(pseudo_row);
    ++pseudo_row;
  };
  for (const auto& row : rows) {
    add_pseudo_row(row.direct_states);
    for (const auto& states : row.source_states) add_pseudo_row(states);
  }
  auto groups = colouring.column_groups();
  std::vector<std::size_t> group_of(size);
  for (std::size_t g = 0; g < groups.size(); ++g)
    for (int column : groups[g]) group_of[static_cast<std::size_t>(column)] = g;
  for (auto& row : rows) {
    detail::CvodeHandles::ChainRule rule;
    rule.sensitivity.assign(row.sources.size(), 0.0);
    rule.base_sources.assign(row.sources.size(), 0.0);
    rule.entries.assign(groups.size(), {});
    const auto add = [&](int source, int column) {
      const auto& rows_here = cv.pattern.rows_of_column[static_cast<std::size_t>(column)];
      const auto place = static_cast<std::size_t>(
          std::lower_bound(rows_here.begin(), rows_here.end(), row.row) - rows_here.begin());
      rule.entries[group_of[static_cast<std::size_t>(column)]].push_back({source, column, place});
    };
    for (std::size_t k = 0; k < row.source_states.size(); ++k)
      for (int column : row.source_states[k]) add(static_cast<int>(k), column);
    for (int column : row.direct_states) add(-1, column);  // after the sources: the remainder
    rule.row = std::move(row);
    cv.chain_rules.push_back(std::move(rule));
  }
  cv.base_derivatives.assign(size, 0.0);
  cv.scratch_derivatives.assign(size, 0.0);
  cv.increments.assign(size, 0.0);
  return groups;
}

// GMRES's preconditioner set-up: a Jacobian when CVODE asks for a fresh one (jok false), with
// the same reuse and carrying as for a direct solver, then P = I - gamma J_B factored.
int preconditioner_setup(realtype t, N_Vector y, N_Vector fy, booleantype jacobian_ok,
                         booleantype* jacobian_current, realtype gamma, void* user_data) {
  auto& cv = cvode_of(user_data);
  *jacobian_current = SUNFALSE;
  if (!jacobian_ok) {
    if (!cv.chain_rules.empty())  // they add to their entries, as CVODE's zeroing lets them
      std::fill_n(SUNSparseMatrix_Data(cv.matrix), SUNSparseMatrix_NNZ(cv.matrix), 0.0);
    const int flag = grouped_jacobian(t, y, fy, cv.matrix, user_data, nullptr, nullptr, nullptr);
    if (flag != 0) return flag;
    ++cv.preconditioner_jacobians;
    *jacobian_current = SUNTRUE;
  }
  return cv.preconditioner->setup(cv.matrix, gamma);
}

int preconditioner_solve(realtype, N_Vector, N_Vector, N_Vector r, N_Vector z, realtype, realtype,
                         int, void* user_data) {
  return cvode_of(user_data).preconditioner->solve(r, z);
}

// J v with the Jacobian of the last set-up: GMRES then solves the system a direct solver would
// (modified Newton), at a sparse product per iteration instead of a right-hand side.
int jacobian_times(N_Vector v, N_Vector product, realtype, N_Vector, N_Vector, void* user_data,
                   N_Vector) {
  return SUNMatMatvec(cvode_of(user_data).matrix, v, product);
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

// The step a warm restart tries first, learnt from the last restart: the step CVODE proposed
// after that segment's first step if it passed the error test at once, else the (reduced) step
// that passed, so a too-bold proposal is not repeated at every breakpoint.
double first_step_after_restart(void* memory) {
  long error_test_failures = 0;
  double step = 0.0;
  check(CVodeGetNumErrTestFails(memory, &error_test_failures), "CVodeGetNumErrTestFails");
  if (error_test_failures == 0)
    check(CVodeGetCurrentStep(memory, &step), "CVodeGetCurrentStep");
  else
    check(CVodeGetLastStep(memory, &step), "CVodeGetLastStep");
  return step;
}

}  // namespace

const std::vector<std::string>& linear_solver_names() {
  static const std::vector<std::string> names{"dense", "band", "klu", "gmres"};
  return names;
}

const std::string& linear_solver_name(LinearSolverKind kind) {
  return linear_solver_names().at(static_cast<std::size_t>(kind));
}

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
  cv.warm_restarts = settings_.restart == RestartKind::warm;
  // Our grouped Jacobian for KLU, and for every matrix kind with warm restarts (which carry
  // it); CVODE's own difference quotients for dense and band otherwise.
  const bool grouped = settings_.linear_solver == LinearSolverKind::klu ||
                       settings_.linear_solver == LinearSolverKind::gmres || cv.warm_restarts;
  if (grouped || settings_.linear_solver == LinearSolverKind::band)
    cv.pattern = system_.jacobian_pattern();
  if (grouped) {
    cv.column_groups = colour_columns(cv, system_.fan_in_rows(kChainFromSources));
    cv.perturbed.assign(static_cast<std::size_t>(size), 0.0);
    cv.perturbed_derivatives.assign(static_cast<std::size_t>(size), 0.0);
  }
  switch (settings_.linear_solver) {
    case LinearSolverKind::dense:
      cv.matrix = SUNDenseMatrix(size, size, cv.sundials);
      cv.linear_solver = SUNLinSol_Dense(cv.state, cv.matrix, cv.sundials);
      break;
    case LinearSolverKind::band:
      cv.matrix = SUNBandMatrix(size, cv.pattern.upper_bandwidth(), cv.pattern.lower_bandwidth(),
                                cv.sundials);
      cv.linear_solver = SUNLinSol_Band(cv.state, cv.matrix, cv.sundials);
      break;
    case LinearSolverKind::klu:
      cv.matrix = SUNSparseMatrix(size, size, cv.pattern.non_zeros(), CSC_MAT, cv.sundials);
      write_structure(cv.pattern, cv.matrix);
      cv.linear_solver = make_klu_solver(cv.state, cv.matrix, cv.sundials);
      break;
    case LinearSolverKind::gmres:
      attach_krylov_solver();
      return;
  }
  if (!cv.matrix || !cv.linear_solver)
    throw std::runtime_error("could not create the linear solver");
  check(CVodeSetLinearSolver(cv.memory, cv.linear_solver, cv.matrix), "CVodeSetLinearSolver");
  if (grouped) check(CVodeSetJacFn(cv.memory, grouped_jacobian), "CVodeSetJacFn");
}

// GMRES, preconditioned on the left by the Jacobian within members (BlockPreconditioner), with
// J v from the Jacobian the preconditioner was built from.
void Integrator::attach_krylov_solver() {
  auto& cv = *cvode_;
  const int size = system_.state_size();
  cv.matrix = SUNSparseMatrix(size, size, cv.pattern.non_zeros(), CSC_MAT, cv.sundials);
  if (!cv.matrix) throw std::runtime_error("could not create the Jacobian's matrix");
  write_structure(cv.pattern, cv.matrix);
  // CVODE sets up before its first solve; zeros until then all the same.
  std::fill_n(SUNSparseMatrix_Data(cv.matrix), SUNSparseMatrix_NNZ(cv.matrix), 0.0);
  cv.preconditioner = std::make_unique<BlockPreconditioner>(
      cv.pattern, system_.jacobian_pattern(JacobianEntries::within_members), cv.state, cv.sundials);
  cv.linear_solver = SUNLinSol_SPGMR(cv.state, SUN_PREC_LEFT, 0, cv.sundials);
  if (!cv.linear_solver) throw std::runtime_error("could not create the GMRES solver");
  check(CVodeSetLinearSolver(cv.memory, cv.linear_solver, nullptr), "CVodeSetLinearSolver");
  check(CVodeSetPreconditioner(cv.memory, preconditioner_setup, preconditioner_solve),
        "CVodeSetPreconditioner");
  check(CVodeSetJacTimes(cv.memory, nullptr, jacobian_times), "CVodeSetJacTimes");
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
    // Computed ones only: CVODE counts the carried ones, and not the preconditioner's.
    statistics_.jacobian_evaluations += cv.preconditioner_jacobians - cv.carried_jacobians;
    cv.carried_jacobians = 0;
    cv.preconditioner_jacobians = 0;
    add(CVodeGetNumLinIters, cv.memory, statistics_.linear_iterations);
    statistics_.rhs_evaluations_for_jacobian += cv.jacobian_rhs_evaluations;
    cv.jacobian_rhs_evaluations = 0;
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
    if (cv.warm_restarts) {
      // A breakpoint changes inputs, not the time scales of the state: the new segment starts
      // with the last Jacobian and with the step learnt at the last restart
      // (first_step_after_restart), instead of CVODE's estimate from scratch.
      cv.offer_carried_jacobian = true;
      if (cv.restart_step > 0.0)
        check(CVodeSetInitStep(cv.memory, cv.restart_step), "CVodeSetInitStep");
      refresh_tolerances();
      return;
    }
  }
  if (settings_.initial_step > 0)
    check(CVodeSetInitStep(cv.memory, settings_.initial_step), "CVodeSetInitStep");
  refresh_tolerances();
}

void Integrator::start_sensitivities(bool first) {
  auto& cv = *cvode_;
  if (!first) {
    check(CVodeSensReInit(cv.memory, CV_STAGGERED, cv.sensitivity_state), "CVodeSensReInit");
    return;
  }
  check(CVodeSensInit(cv.memory, cv.sensitivities->count(), CV_STAGGERED,
                      sensitivity_right_hand_side, cv.sensitivity_state),
        "CVodeSensInit");
  // The scales weigh the sensitivities' errors as the state's (CVODES' p-bar).
  std::vector<double> scales = cv.sensitivities->scales();
  check(CVodeSetSensParams(cv.memory, nullptr, scales.data(), nullptr), "CVodeSetSensParams");
  check(CVodeSensEEtolerances(cv.memory), "CVodeSensEEtolerances");
  check(CVodeSetSensErrCon(cv.memory, settings_.sensitivity_error_control ? SUNTRUE : SUNFALSE),
        "CVodeSetSensErrCon");
}

void Integrator::record_sensitivities(double when, const double* state) {
  auto& cv = *cvode_;
  check(CVodeGetSensDky(cv.memory, when, 0, cv.sensitivity_output), "CVodeGetSensDky");
  for (int j = 0; j < cv.sensitivities->count(); ++j) {
    cv.sensitivities->outputs(j, when, cv.signal_time(when), state,
                              N_VGetArrayPointer(cv.sensitivity_output[j]));
  }
  sensitivity_sink_->record_sensitivities(when, *cv.sensitivities);
}

SolverStatistics Integrator::run(double t0, double t_end, OutputTimes output,
                                 ForwardSensitivities& sensitivities, SensitivitySink& sink) {
  if (settings_.method == IntegrationMethod::adams)
    throw std::invalid_argument("forward sensitivities need the BDF method");
  auto& cv = *cvode_;
  if (cv.sensitivities) throw std::logic_error("an integrator tracks sensitivities once");
  cv.sensitivities = &sensitivities;
  cv.sensitivity_count = sensitivities.count();
  cv.sensitivity_state = N_VCloneVectorArray(sensitivities.count(), cv.state);
  cv.sensitivity_output = N_VCloneVectorArray(sensitivities.count(), cv.state);
  for (int j = 0; j < sensitivities.count(); ++j)
    cv.sensitivity_pointers.push_back(N_VGetArrayPointer(cv.sensitivity_state[j]));
  sensitivity_sink_ = &sink;
  return run(t0, t_end, output, sink);
}

void Integrator::report_progress(const Progress& progress, double reached, long steps) {
  try {
    progress(reached, steps);
  } catch (const StopRequest& request) {
    accumulate_statistics();
    throw RunInterrupted(request.what(), reached, statistics_);
  }
}

SolverStatistics Integrator::run(double t0, double t_end, OutputTimes output, OutputSink& sink,
                                 const Progress& progress) {
  begin(t0, t_end, output, sink, InstantSplit::whole);
  advance(t_end, progress);
  return statistics_;
}

void Integrator::begin(double t0, double t_end, OutputTimes output, OutputSink& sink,
                       InstantSplit split) {
  auto& cv = *cvode_;
  double* state = N_VGetArrayPointer(cv.state);
  system_.initialize(context_, t0, state);
  course_ = std::make_unique<detail::Course>(detail::Course{
      t0, t_end, t0, detail::OutputGrid(std::max(t0, output.start), t_end, output.interval), &sink,
      split == InstantSplit::held});
  // Sampled components take their first sample.
  if (course_->hold_instants)
    system_.begin_instant(context_, t0, t0, state);
  else
    system_.at_breakpoint(context_, t0, t0, state);
  course_->instant_held = course_->hold_instants;
  if (cv.sensitivities) cv.sensitivities->initialize(t0, cv.sensitivity_pointers);
  statistics_ = {};
}

double Integrator::time() const {
  return course_ ? course_->t : 0.0;
}

SolverStatistics Integrator::statistics() {
  if (!course_ || course_->ended) return statistics_;
  // CVODE's counters since the last restart, added to a copy: the restart or the end adds them
  // to the run's own count.
  auto& cv = *cvode_;
  const SolverStatistics before = statistics_;
  const long carried = cv.carried_jacobians;
  const long preconditioner = cv.preconditioner_jacobians;
  const long jacobian_rhs = cv.jacobian_rhs_evaluations;
  accumulate_statistics();
  const SolverStatistics so_far = statistics_;
  statistics_ = before;
  cv.carried_jacobians = carried;
  cv.preconditioner_jacobians = preconditioner;
  cv.jacobian_rhs_evaluations = jacobian_rhs;
  return so_far;
}

void Integrator::advance(double until, const Progress& progress) {
  if (!course_) throw std::logic_error("Integrator::advance before begin");
  auto& cv = *cvode_;
  detail::Course& course = *course_;
  double* state = N_VGetArrayPointer(cv.state);
  const double t0 = course.t0;
  const double t_end = course.t_end;
  until = std::min(until, t_end);
  if (course.instant_held) {  // the instant the last call stopped at, taken to its end
    system_.end_instant(context_, course.t, course.t == t0 ? t0 : course.t - time_margin(course.t),
                        state);
    course.instant_held = false;
  }
  detail::OutputGrid& grid = course.grid;
  double t = course.t;
  while (t < until) {
    // Breakpoints closer than a few rounding errors are one event; a signal composed from
    // shifted pieces may report an instant that is t itself after rounding.
    const double margin = time_margin(t);
    double stop = system_.next_breakpoint_after(context_, t);
    while (stop <= t + 2.0 * margin)
      stop = system_.next_breakpoint_after(context_, std::max(stop, t + 2.0 * margin));
    if (cv.sensitivities) cv.sensitivities->check_breakpoint(t, stop);
    stop = std::min(stop, until);
    // Stepping, a time asked for within rounding of a breakpoint is that breakpoint (a master
    // that adds its step to the time it reached lands an ulp beside the sample instants).
    if (course.hold_instants && until > stop && until - stop <= 2.0 * time_margin(until))
      stop = until;
    const bool last_segment = stop >= t_end;
    start_segment(t, t == t0);
    if (cv.sensitivities) start_sensitivities(t == t0);
    check(CVodeSetStopTime(cv.memory, stop), "CVodeSetStopTime");
    cv.segment_start = t + margin;
    cv.segment_end = stop - time_margin(stop);
    ++statistics_.segments;
    int collapsed_steps = 0;  // a restart's first steps are small by design
    const long segment_first_step = course.steps_taken + 1;
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
      const long steps_taken = cv.steps = ++course.steps_taken;
      if (steps_taken == segment_first_step) {
        cv.restart_step = first_step_after_restart(cv.memory);
        cv.offer_carried_jacobian = false;
      }
      if (steps_taken > settings_.max_steps) {
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
        course.sink->record(when, context_.signals());
        if (cv.sensitivities) record_sensitivities(when, N_VGetArrayPointer(cv.scratch));
        // A long step may cover many output times: observers hear of them too.
        if (++statistics_.output_samples % kOutputsPerProgress == 0 && progress)
          report_progress(progress, when, steps_taken);
      }
      if (progress) report_progress(progress, reached, steps_taken);
    }
    t = course.t = stop;
    if (t < t_end) {
      if (t >= until && course.hold_instants) {
        system_.begin_instant(context_, t, t - time_margin(t), state);
        course.instant_held = true;
      } else {
        system_.at_breakpoint(context_, t, t - time_margin(t), state);
      }
      if (cv.sensitivities) {
        check(CVodeGetSens(cv.memory, &reached, cv.sensitivity_state), "CVodeGetSens");
        cv.sensitivities->at_breakpoint(t, t - time_margin(t), state, cv.sensitivity_pointers);
      }
    }
  }
  if (t >= t_end && !course.ended) {
    course.ended = true;
    accumulate_statistics();
  }
}

}  // namespace tcpmsim
