#pragma once

#include <limits>
#include <span>
#include <string>
#include <vector>

namespace tcpmsim {

// A continuous state a component owns. Units are SI; the tolerance is the default absolute
// tolerance CVODE uses for this entry unless the scenario overrides it.
struct StateDeclaration {
  std::string name;
  std::string unit;
  double absolute_tolerance;
};

// A named, unit-carrying value a component publishes for others (and for the recorder).
// An *observed* output is expensive and feeds nothing continuous (a coil's inductance from
// Maxwell's O(N^2) sum): it is computed only for the record and at breakpoints, never inside
// the right-hand side, and may be read only by sampled inputs.
struct OutputDeclaration {
  std::string name;
  std::string unit;
  bool observed = false;
};

// An input port. A direct-feedthrough input is read while computing outputs; the engine
// orders components so that such inputs are computed first. Inputs read only for derivatives
// impose no order, which is what lets a thermal node and a temperature-dependent drive
// feed each other without an algebraic loop.
// A sampled input is read only at breakpoints (a controller's sample instants), so it may
// read observed outputs.
struct InputDeclaration {
  std::string name;
  bool direct_feedthrough;
  bool sampled = false;
};

// Everything a component sees during one evaluation. `signal_time` is the time at which
// prescribed signals are sampled: equal to `time` except at the end of an integration segment,
// where it is the left limit so that a step at the segment end is not seen early.
struct Evaluation {
  double time;
  double signal_time;
  const double* state;
  double* signals;
};

class Signal;

inline constexpr double kNoBreakpoint = std::numeric_limits<double>::infinity();

// Structural dependence of one of a component's derivatives or outputs on its own states
// and inputs (local indices). Used to build the Jacobian sparsity pattern.
struct Dependencies {
  std::vector<int> states;
  std::vector<int> inputs;
};

// A piece of the model that owns a slice of the state vector, its parameters and its named
// outputs. The System assigns offsets and wires inputs to outputs; a component never reaches
// into another one.
class Component {
 public:
  Component(std::string group, std::string kind);
  virtual ~Component() = default;
  Component(const Component&) = delete;
  Component& operator=(const Component&) = delete;

  // `group` is the user-facing entity ("muscle", "drive", "load"); outputs are recorded under
  // /group/name. `kind` names the model ("thermal_node").
  const std::string& group() const { return group_; }
  const std::string& kind() const { return kind_; }

  virtual std::vector<StateDeclaration> states() const { return {}; }
  virtual std::vector<OutputDeclaration> outputs() const { return {}; }
  virtual std::vector<InputDeclaration> inputs() const { return {}; }

  // Writes the component's initial state. Called in evaluation order with the outputs of
  // upstream components already computed, so initial conditions may depend on inputs
  // (a relaxed dashpot starts at the imposed deflection).
  virtual void initialize(const Evaluation& evaluation, std::span<double> own_state) const;

  // Computes all non-observed outputs from the component's state, its inputs and time.
  virtual void compute_outputs(const Evaluation& evaluation) const;
  // Computes the observed outputs; called after compute_outputs, for the record and at
  // breakpoints only. Must not allocate.
  virtual void compute_observations(const Evaluation& evaluation) const;

  // Writes d(own state)/dt into the global derivative vector. Must not allocate.
  virtual void compute_derivatives(const Evaluation& evaluation, double* derivatives) const;

  // The first time strictly after t at which this component is discontinuous (signal steps,
  // switching edges, sample instants). The integrator stops there and restarts.
  virtual double next_breakpoint_after(double t) const;

  // Called at a breakpoint (and once at the start of a run), after outputs were computed with
  // the left-limit inputs. Sampled systems update their held values here.
  virtual void at_breakpoint(const Evaluation& evaluation);

  // Called at every breakpoint before any component acts, with outputs computed from the
  // left-limit inputs: a component that is also an instrument publishes its reading here,
  // ahead of the estimators, even if it acts as an actuator later in the instant.
  virtual void sense(const Evaluation& evaluation);

  // Within one instant, components act in this order: instruments (0) publish a measurement,
  // estimators (1) use it, controllers (2) use the estimates, actuators (3) apply commands.
  enum class SamplingStage { instrument = 0, estimator = 1, controller = 2, actuator = 3 };
  virtual SamplingStage sampling_stage() const { return SamplingStage::instrument; }

  // Zero-crossing events: g_k(t, y) whose sign changes CVODE locates to within rounding. A
  // component with events writes its g values and reacts to a located crossing; the state is
  // continuous across it (a discontinuity must be a breakpoint).
  virtual int event_count() const { return 0; }
  // +1: only rising crossings, -1: only falling, 0: both.
  virtual int event_direction(int /*index*/) const { return 0; }
  virtual void event_functions(const Evaluation& evaluation, double* values) const;
  virtual void at_event(int index, const Evaluation& evaluation);

  // May change the tolerances of the component's own states for the coming steps (called at
  // every segment start and after every event): a state that matters only at some times need
  // not be resolved to the configured tolerance at others. Both spans hold the configured
  // values on entry.
  virtual void adapt_tolerances(std::span<double> absolute, std::span<double> relative) const;

  // Structural dependencies, for sparse and banded Jacobians. The defaults say "everything
  // the component owns or reads", which is exact for small components.
  virtual Dependencies derivative_dependencies(int state_index) const;
  virtual Dependencies output_dependencies(int output_index) const;

  // A short description of the prescribed inputs (signals) this component applies, for the
  // record. Empty when the component has none.
  struct SignalRecord {
    std::string name;
    std::string unit;
    const Signal* signal;
  };
  virtual std::vector<SignalRecord> signal_records() const { return {}; }

 protected:
  double state(const Evaluation& evaluation, int index) const {
    return evaluation.state[state_offset_ + index];
  }
  double input(const Evaluation& evaluation, int index) const {
    return evaluation.signals[input_signal_index_[static_cast<std::size_t>(index)]];
  }
  void set_output(const Evaluation& evaluation, int index, double value) const {
    evaluation.signals[output_offset_ + index] = value;
  }
  void set_derivative(double* derivatives, int index, double value) const {
    derivatives[state_offset_ + index] = value;
  }

 private:
  friend class System;
  std::string group_;
  std::string kind_;
  int state_offset_ = 0;
  int output_offset_ = 0;
  std::vector<int> input_signal_index_;
};

}  // namespace tcpmsim
