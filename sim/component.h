#pragma once

#include <limits>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "sim/parameters.h"

namespace tcpmsim {

class Context;
class Signal;

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
// the right-hand side, and may be read only by sampled inputs. An output that is not
// *recorded* is a port only (an attached branch's stiffness for the SLS to solve with).
struct OutputDeclaration {
  std::string name;
  std::string unit;
  bool observed = false;
  bool recorded = true;
};

// How many outputs an input reads.
enum class InputArity {
  one,       // exactly one source
  optional,  // none or one (a component that adapts to what it is connected to)
  many,      // any number: a port that fans in (a joint's muscles, attached effect terms)
};

// An input port. A direct-feedthrough input is read while computing outputs; the engine
// orders components so that such inputs are computed first. Inputs read only for derivatives
// impose no order, which is what lets a thermal node and a temperature-dependent drive
// feed each other without an algebraic loop.
// A sampled input is read only at breakpoints (a controller's sample instants), so it may
// read observed outputs.
// An input between members couples separate members of a group (a bundle's touching
// neighbours): the whole Jacobian holds its entries, a block preconditioner leaves them out.
struct InputDeclaration {
  std::string name;
  bool direct_feedthrough;
  bool sampled = false;
  InputArity arity = InputArity::one;
  bool between_members = false;
};

// A prescribed signal a component applies (an imposed deflection, a power demand, an ambient
// temperature). Its numeric parameters become the component's signal parameters, and a run
// context may replace it by a copy with other values.
struct SignalDeclaration {
  std::string name;  // recorded as /inputs/<group>.<name>
  std::string unit;
  const Signal* signal;
};

// An input set from outside the system while a run goes on (sim/stepper.h: a controller in
// Python, an FMU's master): recorded as the component's output of the same name.
struct ExternalInputDeclaration {
  std::string name;  // "<group>.<name>" to the master
  std::string unit;
};

// Whatever a component keeps per run, outside the continuous state: its parameters as a run
// context sets them, what it derives from them, and its discrete state (held outputs, filter
// buffers, random streams). Created by the component when a run starts.
class RunState {
 public:
  virtual ~RunState() = default;
};

// What a component sees when its run state is created.
struct RunSetup {
  std::span<const double> parameters;  // its own, in declaration order, SI
  const Context& context;              // everything else: other parameters, signals
};

// Everything a component sees during one evaluation. `signal_time` is the time at which
// prescribed signals are sampled: equal to `time` except at the end of an integration segment,
// where it is the left limit so that a step at the segment end is not seen early. The pointers
// lead into the run context.
struct Evaluation {
  double time;
  double signal_time;
  const double* state;
  double* signals;
  const double* parameters;
  const std::unique_ptr<RunState>* run_states;
  const Signal* const* prescribed;
};

inline constexpr double kNoBreakpoint = std::numeric_limits<double>::infinity();

// Structural dependence of one of a component's derivatives or outputs on its own states
// and inputs (local indices). Used to build the Jacobian sparsity pattern.
struct Dependencies {
  std::vector<int> states;
  std::vector<int> inputs;
};

// A piece of the model that owns a slice of the state vector, its parameters and its named
// outputs. The System assigns offsets and wires inputs to outputs; a component never reaches
// into another one. After assembly a component is immutable: everything a run changes lives in
// the run context, which every evaluation carries.
class Component {
 public:
  Component(std::string group, std::string kind);
  virtual ~Component() = default;
  Component(const Component&) = delete;
  Component& operator=(const Component&) = delete;

  // `group` names the instance the component belongs to ("muscle", "left", or
  // "left/maxwell_branch" for a part attached to it); outputs are recorded under /group/name.
  // `kind` names the model ("thermal_node").
  const std::string& group() const { return group_; }
  const std::string& kind() const { return kind_; }

  virtual std::vector<StateDeclaration> states() const { return {}; }
  virtual std::vector<OutputDeclaration> outputs() const { return {}; }
  virtual std::vector<InputDeclaration> inputs() const { return {}; }
  // Numeric parameters a run context may change, with their values as built.
  virtual std::vector<ParameterDeclaration> parameters() const { return {}; }
  virtual std::vector<SignalDeclaration> signals() const { return {}; }
  // Inputs a master outside the system sets as the run goes (none by default). The master
  // holds a value within external_input_range from the instant it sets it on; it sets it
  // between System::begin_instant and end_instant, where the controllers act.
  virtual std::vector<ExternalInputDeclaration> external_inputs() const { return {}; }
  virtual std::pair<double, double> external_input_range(const Evaluation& evaluation,
                                                         int index) const;
  virtual void hold_external_input(const Evaluation& evaluation, int index, double value) const;

  // Called once its inputs are wired: a component whose inputs are optional says here whether
  // what is connected makes sense (the problem, or "").
  virtual std::string check_connections() const;

  // Creates the run state from the context's values of this component's parameters (called
  // when a run starts). Components without run state return nullptr.
  virtual std::unique_ptr<RunState> create_run_state(const RunSetup& setup) const;
  // Conditions between parameters that a single range cannot state ("P_min < P_max"): returns
  // the problem, naming the keys it concerns relative to the component, or "" (the error
  // names the component). Called when a run starts with values a context changed.
  virtual std::string check_parameters(const RunSetup& setup) const;

  // Writes the component's initial state. Called in evaluation order with the outputs of
  // upstream components already computed, so initial conditions may depend on inputs
  // (a relaxed dashpot starts at the imposed deflection); then once more, with every output of
  // the first round, so that they may also depend on inputs read without feedthrough (an
  // attached branch starts relaxed at the muscle's deflection).
  virtual void initialize(const Evaluation& evaluation, std::span<double> own_state) const;

  // Computes all non-observed outputs from the component's state, its inputs and time.
  virtual void compute_outputs(const Evaluation& evaluation) const;
  // Computes the observed outputs; called after compute_outputs, for the record and at
  // breakpoints only. Must not allocate.
  virtual void compute_observations(const Evaluation& evaluation) const;

  // Writes d(own state)/dt into the global derivative vector. Must not allocate.
  virtual void compute_derivatives(const Evaluation& evaluation, double* derivatives) const;

  // The first time strictly after evaluation.time at which this component is discontinuous
  // (signal steps, switching edges, sample instants). The integrator stops there and restarts.
  // The evaluation has no state (null): breakpoints follow from time, signals and run state.
  virtual double next_breakpoint_after(const Evaluation& evaluation) const;

  // Called at a breakpoint (and once at the start of a run), after outputs were computed with
  // the left-limit inputs. Sampled systems update their held values (in their run state) here.
  virtual void at_breakpoint(const Evaluation& evaluation) const;

  // Called at every breakpoint before any component acts, with outputs computed from the
  // left-limit inputs: a component that is also an instrument publishes its reading here,
  // ahead of the estimators, even if it acts as an actuator later in the instant.
  virtual void sense(const Evaluation& evaluation) const;

  // Within one instant, components act in this order: instruments (0) publish a measurement,
  // estimators (1) use it, controllers (2) use the estimates, actuators (3) apply commands.
  enum class SamplingStage { instrument = 0, estimator = 1, controller = 2, actuator = 3 };
  virtual SamplingStage sampling_stage() const { return SamplingStage::instrument; }

  // Whether the component changes its run state at breakpoints or events (a sampled
  // controller's held command, a drive's switching edges): a jump that forward sensitivities,
  // which follow the continuous state only, cannot pass through.
  virtual bool acts_discretely() const { return false; }

  // Zero-crossing events: g_k(t, y) whose sign changes CVODE locates to within rounding. A
  // component with events writes its g values and reacts to a located crossing; the state is
  // continuous across it (a discontinuity must be a breakpoint).
  virtual int event_count() const { return 0; }
  // +1: only rising crossings, -1: only falling, 0: both.
  virtual int event_direction(int /*index*/) const { return 0; }
  virtual void event_functions(const Evaluation& evaluation, double* values) const;
  virtual void at_event(int index, const Evaluation& evaluation) const;

  // May change the tolerances of the component's own states for the coming steps (called at
  // every segment start and after every event): a state that matters only at some times need
  // not be resolved to the configured tolerance at others. Both spans hold the configured
  // values on entry. The evaluation carries parameters and run state only (time 0, no state).
  virtual void adapt_tolerances(const Evaluation& evaluation, std::span<double> absolute,
                                std::span<double> relative) const;

  // Structural dependencies, for sparse and banded Jacobians. The defaults say "everything
  // the component owns or reads", which is exact for small components.
  virtual Dependencies derivative_dependencies(int state_index) const;
  virtual Dependencies output_dependencies(int output_index) const;

  // The number of outputs wired to an input (known after assembly): 0 or 1 for an optional
  // input, any number for a fan-in.
  int source_count(int input) const { return fan_in_count_[static_cast<std::size_t>(input)]; }

 protected:
  double state(const Evaluation& evaluation, int index) const {
    return evaluation.state[state_offset_ + index];
  }
  // The (first) source of an input.
  double input(const Evaluation& evaluation, int index) const {
    return evaluation.signals[first_source_[static_cast<std::size_t>(index)]];
  }
  // Source k of a fan-in input.
  double input(const Evaluation& evaluation, int index, int k) const {
    return evaluation.signals[fan_in_sources_[static_cast<std::size_t>(
        fan_in_begin_[static_cast<std::size_t>(index)] + k)]];
  }
  // The sum of a fan-in input's sources, in connection order (0 with none).
  double input_sum(const Evaluation& evaluation, int index) const {
    const int count = source_count(index);
    if (count == 0) return 0.0;
    double sum = input(evaluation, index, 0);
    for (int k = 1; k < count; ++k) sum += input(evaluation, index, k);
    return sum;
  }
  double parameter(const Evaluation& evaluation, int index) const {
    return evaluation.parameters[parameter_offset_ + index];
  }
  void set_output(const Evaluation& evaluation, int index, double value) const {
    evaluation.signals[output_offset_ + index] = value;
  }
  void set_derivative(double* derivatives, int index, double value) const {
    derivatives[state_offset_ + index] = value;
  }
  // The signal declared at `index` of signals(), as the run context has it.
  const Signal& signal(const Evaluation& evaluation, int index) const {
    return *evaluation.prescribed[signal_offset_ + index];
  }
  // The same, where there is no evaluation (when a run starts: check_parameters,
  // create_run_state).
  const Signal& signal(const Context& context, int index) const;
  template <typename T>
  const T& run_state(const Evaluation& evaluation) const {
    return static_cast<const T&>(*evaluation.run_states[index_]);
  }
  // For the methods that act (at_breakpoint, sense, at_event), and for scratch space in
  // compute_observations: the run state is the context's.
  template <typename T>
  T& mutable_run_state(const Evaluation& evaluation) const {
    return static_cast<T&>(*evaluation.run_states[index_]);
  }

 private:
  friend class System;
  friend class Context;
  std::string group_;
  std::string kind_;
  int index_ = 0;
  int state_offset_ = 0;
  int output_offset_ = 0;
  int parameter_offset_ = 0;
  int signal_offset_ = 0;
  std::vector<int> first_source_;    // per input: its first source's signal index, or -1
  std::vector<int> fan_in_begin_;    // per input: where its sources start in fan_in_sources_
  std::vector<int> fan_in_count_;    // per input: how many sources
  std::vector<int> fan_in_sources_;  // every input's sources, input by input
};

}  // namespace tcpmsim
