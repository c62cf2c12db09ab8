#pragma once

#include <functional>
#include <limits>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "sim/context.h"
#include "sim/system.h"

namespace tcpmsim {

namespace detail {
struct CvodeHandles;
struct Course;
}  // namespace detail

// The Newton iteration's linear solver: direct (dense, band, KLU on the sparse pattern), or
// GMRES preconditioned by the Jacobian within members (KLU on each member's block), whose cost
// stays linear in the members when their coupling (a bundle's contact conduction) makes the
// whole matrix's LU fill grow faster.
enum class LinearSolverKind { dense, band, klu, gmres };
// The names configs give them (solver.linear_solver), in LinearSolverKind's order.
const std::vector<std::string>& linear_solver_names();
const std::string& linear_solver_name(LinearSolverKind kind);

// BDF with Newton iteration for stiff systems (the muscles: thermal and mechanical time
// constants seconds apart); Adams-Moulton with fixed-point iteration for non-stiff oscillatory
// ones (an undamped winding chain, whose every mode must be resolved anyway).
enum class IntegrationMethod { bdf, adams };

// What a restart at a breakpoint keeps. Cold: CVODE starts afresh (its own initial step
// estimate and a new Jacobian). Warm: the new segment starts from the last step size and the
// last Jacobian (recomputed as soon as the Newton iteration fails). Either way KLU keeps its
// symbolic analysis, since the pattern never changes.
enum class RestartKind { cold, warm };

struct SolverSettings {
  double relative_tolerance = 1e-6;
  std::vector<double> absolute_tolerances;  // one per state; empty: the states' defaults
  IntegrationMethod method = IntegrationMethod::bdf;
  LinearSolverKind linear_solver = LinearSolverKind::dense;  // BDF's Newton iteration only
  RestartKind restart = RestartKind::cold;
  double max_step = 0.0;      // 0: no limit
  double initial_step = 0.0;  // 0: CVODE's estimate
  long max_steps = 50'000'000;
  // Forward sensitivities under CVODES' local error test with the state (errconS). Off, they
  // ride on the steps the state chooses: a fit's Jacobian needs no more, and its runs take about
  // a quarter fewer steps.
  bool sensitivity_error_control = false;
};

// CVODE's counters, summed over all integration segments.
struct SolverStatistics {
  long steps = 0;
  long rhs_evaluations = 0;
  long rhs_evaluations_for_jacobian = 0;
  long jacobian_evaluations = 0;
  long linear_solver_setups = 0;
  long error_test_failures = 0;
  long nonlinear_iterations = 0;
  long nonlinear_convergence_failures = 0;
  long linear_iterations = 0;  // GMRES's (0 for a direct solver)
  long segments = 0;           // hard stops + 1
  long events = 0;             // located zero crossings
  long output_samples = 0;
};

// When to record: every `interval` from `start` (default: the start of the run), and the end.
struct OutputTimes {
  OutputTimes(double every,
              double from = -std::numeric_limits<double>::infinity())  // NOLINT: implicit
      : interval(every), start(from) {}
  double interval;
  double start;
};

// Receives the outputs at each output time.
class OutputSink {
 public:
  virtual ~OutputSink() = default;
  virtual void record(double time, std::span<const double> signals) = 0;
};

class ForwardSensitivities;

// Receives the outputs and, right after them, their sensitivities to the tracked parameters
// (ForwardSensitivities::output_sensitivity) at each output time.
class SensitivitySink : public OutputSink {
 public:
  virtual void record_sensitivities(double time, const ForwardSensitivities& sensitivities) = 0;
};

// A run that ended before its end time: why, the time reached and the statistics so far.
class RunEnded : public std::runtime_error {
 public:
  RunEnded(const std::string& reason, double time, SolverStatistics statistics)
      : std::runtime_error(reason), time_(time), statistics_(statistics) {}
  double time() const { return time_; }
  const SolverStatistics& statistics() const { return statistics_; }

 private:
  double time_;
  SolverStatistics statistics_;
};

// The solver could not go on (the CVODE flag, the time, the worst state entries).
class SolverFailure : public RunEnded {
 public:
  using RunEnded::RunEnded;
};

// Thrown by a progress observer to end a run early (an interrupt, a cancelled job); the run
// stops after the step it reports and is ended with RunInterrupted.
class StopRequest : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;  // the reason, e.g. "interrupted by SIGTERM"
};

// A run ended early at a StopRequest. Every output time up to time() has been handed to the
// sink.
class RunInterrupted : public RunEnded {
 public:
  using RunEnded::RunEnded;
};

// CVODE (BDF, Newton) over a System and one run Context. Steps with CV_ONE_STEP, writes
// outputs by interpolation (CVodeGetDky) on a uniform grid, stops hard at every breakpoint the
// components declare and restarts there with CVodeReInit. The state CVODE advances is the
// context's.
class Integrator {
 public:
  Integrator(const System& system, Context& context, SolverSettings settings);
  ~Integrator();
  Integrator(const Integrator&) = delete;
  Integrator& operator=(const Integrator&) = delete;

  // Called after every step, and after every kOutputsPerProgress output samples within a step;
  // may throw StopRequest to end the run (as RunInterrupted).
  static constexpr long kOutputsPerProgress = 4096;
  using Progress = std::function<void(double time, long steps)>;

  // Integrates from t0 to t_end and records outputs at start + k * interval (and t_end).
  // Throws SolverFailure with the CVODE flag, the time and the worst state entries.
  SolverStatistics run(double t0, double t_end, OutputTimes output, OutputSink& sink,
                       const Progress& progress = {});
  // The same, integrating forward sensitivities beside the state (CVODES, staggered, with the
  // sensitivities under error control) and handing `sink` the outputs' sensitivities too.
  // Throws std::invalid_argument with the Adams method (sensitivities need Newton's iteration).
  SolverStatistics run(double t0, double t_end, OutputTimes output,
                       ForwardSensitivities& sensitivities, SensitivitySink& sink);

  // Step by step (sim/stepper.h): begin() starts a run at t0 and advance() integrates it on to
  // a time, any number of times, until t_end; run() is begin() and advance(t_end) in one.
  // With InstantSplit::held every call leaves the instant it stops at (t0 for begin) half taken:
  // its instruments and estimators have acted (System::begin_instant), its controllers and
  // actuators act when the next advance() starts (System::end_instant). Something outside the
  // system (a controller in Python, an FMU's master) reads the estimates and sets its commands
  // in between, exactly where a controller component of the system would act.
  enum class InstantSplit { whole, held };
  void begin(double t0, double t_end, OutputTimes output, OutputSink& sink,
             InstantSplit split = InstantSplit::whole);
  // Integrates to min(until, t_end); the run's outputs at the output times it passes go to the
  // sink. Throws what run() throws.
  void advance(double until, const Progress& progress = {});
  double time() const;  // the time reached
  // CVODE's counters of the run so far.
  SolverStatistics statistics();

 private:
  void attach_linear_solver();
  void attach_krylov_solver();
  void start_segment(double start, bool first);
  void start_sensitivities(bool first);
  void record_sensitivities(double when, const double* state);
  void refresh_tolerances();
  void accumulate_statistics();
  SolverFailure failure(const std::string& headline);
  // Calls `progress`; a StopRequest from it becomes RunInterrupted with the statistics so far.
  void report_progress(const Progress& progress, double reached, long steps);

  std::unique_ptr<detail::CvodeHandles> cvode_;
  std::unique_ptr<detail::Course> course_;
  const System& system_;
  Context& context_;
  SolverSettings settings_;
  SolverStatistics statistics_;
  SensitivitySink* sensitivity_sink_ = nullptr;
};

}  // namespace tcpmsim
