#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "sim/component.h"
#include "sim/sparsity.h"

namespace tcpmsim {

class Context;

// Where a named quantity lives after assembly.
struct StateInfo {
  std::string name;  // "group.state"
  std::string unit;
  double absolute_tolerance;
  const Component* owner;
};

struct ChannelInfo {
  std::string group;
  std::string name;
  std::string unit;
  int signal_index;
  bool observed;
  bool recorded;
};

// A numeric parameter of the assembled model: a component's, or one of the signals a component
// applies. A derived parameter follows others by a rule and cannot be set itself.
struct ParameterInfo {
  ParameterDeclaration declaration;
  std::string derived_from;  // non-empty: how it is derived
};

// An input a master outside the system sets while a run goes on (Component::external_inputs).
struct ExternalInputInfo {
  std::string name;  // "controller.power_command"
  std::string unit;
  const Component* owner;
  int index;  // in the owner's external_inputs()
};

// A prescribed signal of the assembled model, with its parameters' place in the parameter list.
struct SignalSlot {
  std::string group;
  std::string name;
  std::string unit;
  const Signal* signal;  // as built
  int first_parameter = 0;
  int parameter_count = 0;
};

// A rule that sets a derived parameter from a prepared context (other parameters, signals).
using ParameterRule = std::function<double(const Context&)>;
// A condition between parameters of different components: the problem, or "".
using ParameterConstraint = std::function<std::string(const Context&)>;

class SystemBuilder;

// Instances that are alike and recorded together: the members "<name>/<member>" of a bundle.
struct MemberSet {
  std::string name;                  // "b"
  std::vector<std::string> members;  // "m000", ...: the instances "b/m000", ...
  // Fixed per-member facts the record keeps beside the traces (a bundle's packing: where each
  // member sits), one value per member.
  struct Property {
    std::string name;  // "centre_x"
    std::string unit;
    std::vector<double> values;
  };
  std::vector<Property> properties;
};

// A derivative that reads many states through one fan-in input (a mass hanging on every muscle
// of a bundle): its Jacobian row is dense, and finite differences over structurally orthogonal
// columns would need a group per column. The Integrator finds its entries by the chain rule
// through the fan-in's source signals instead.
// Which entries of the Jacobian's pattern: all, or those within members only.
enum class JacobianEntries { all, within_members };

struct FanInRow {
  int row = 0;                                  // the derivative's state index
  int component = 0;                            // its owner
  std::vector<int> sources;                     // the fan-in's source signals
  std::vector<std::vector<int>> source_states;  // the states each source depends on
  std::vector<int> direct_states;               // the states the row reads otherwise
};

// Components assembled into one ODE system y' = f(t, y). The System owns the components,
// assigns each its slice of the state vector, of the output vector and of the parameter vector,
// wires inputs to outputs and evaluates everything in an order that respects direct
// feedthrough. It is immutable: every evaluation takes the run Context that holds what a run
// changes (state, outputs, parameters, the components' run states), so one System can serve
// many runs at once, each with its own context.
class System {
 public:
  System(const System&) = delete;
  System& operator=(const System&) = delete;

  int state_size() const { return static_cast<int>(states_.size()); }
  int signal_size() const { return static_cast<int>(channels_.size()); }
  const std::vector<StateInfo>& states() const { return states_; }
  const std::vector<ChannelInfo>& channels() const { return channels_; }
  const std::vector<std::unique_ptr<Component>>& components() const { return components_; }
  const std::vector<ParameterInfo>& parameters() const { return parameters_; }
  const std::vector<SignalSlot>& signal_slots() const { return signal_slots_; }
  const std::vector<MemberSet>& member_sets() const { return member_sets_; }
  const std::vector<ExternalInputInfo>& external_inputs() const { return external_inputs_; }
  // The values external input `input` may take in the context's (prepared) run.
  std::pair<double, double> external_input_range(Context& context, int input) const;
  // Holds `value` on external input `input` from now on (between begin_instant and end_instant).
  // Throws std::invalid_argument naming the input and its range for a value outside it.
  void hold_external_input(Context& context, int input, double value) const;
  int signal_index(std::string_view output) const;                  // "group.name"; -1 if absent
  std::optional<int> parameter_index(std::string_view path) const;  // "muscle.mechanics.k2"
  std::optional<int> signal_slot(std::string_view group, std::string_view name) const;

  // The output wired to `consumer`'s input `input` (its first source), or nullptr when nothing
  // is (or the component has no such input).
  const ChannelInfo* source_of(const Component& consumer, std::string_view input) const;

  // The first component of type T, or nullptr.
  template <typename T>
  const T* find() const {
    for (const auto& component : components_) {
      if (const auto* found = dynamic_cast<const T*>(component.get())) return found;
    }
    return nullptr;
  }

  // Makes the context ready for a run: signals rebuilt where their parameters changed, derived
  // parameters computed, conditions checked (ParameterError), run states created afresh.
  void prepare(Context& context) const;
  // prepare() (unless the context is prepared already: prepared since its last run and since
  // its last parameter change), then the initial state.
  void initialize(Context& context, double time, double* state) const;
  // Computes every output, observed ones included; afterwards context.signals() holds them.
  void evaluate_outputs(Context& context, double time, double signal_time,
                        const double* state) const;
  // f(t, y). Allocation-free.
  void evaluate_derivatives(Context& context, double time, double signal_time, const double* state,
                            double* derivatives) const;

  double next_breakpoint_after(Context& context, double time) const;
  // Lets sampled components act at a breakpoint. Outputs are recomputed with signals sampled
  // at `left_limit` (just before the instant) first, so a controller samples what was true
  // just before it acts.
  void at_breakpoint(Context& context, double time, double left_limit, const double* state) const;
  // The same in two halves, at_breakpoint being one and then the other: the instruments sense
  // and the instruments and estimators act; then the controllers and actuators act and the
  // outputs are recomputed. Between them a controller outside the system (sim/stepper.h) reads
  // the estimates and sets its commands.
  void begin_instant(Context& context, double time, double left_limit, const double* state) const;
  void end_instant(Context& context, double time, double left_limit, const double* state) const;

  // Lets components adapt per-state tolerances; both arrays hold the configured ones on entry.
  void adapt_tolerances(Context& context, double* absolute, double* relative) const;

  // Events: all components' zero-crossing functions, concatenated.
  int event_count() const { return event_count_; }
  std::vector<int> event_directions() const;
  void evaluate_events(Context& context, double time, double signal_time, const double* state,
                       double* values) const;
  // Tells the owners of the crossed events (flags[k] != 0) where they are.
  void at_events(Context& context, double time, double signal_time, const double* state,
                 const int* flags) const;

  // Self-check for tests: every component, evaluated at (time, state), writes exactly its own
  // outputs and derivatives and nothing else. Returns a description of the first violation,
  // or an empty string.
  std::string check_component_contracts(Context& context, double time, const double* state) const;

  // Structural non-zeros of df/dy (row = derivative, column = state): all of them, or only
  // those within members (without what inputs between members carry), a block
  // preconditioner's pattern.
  SparsityPattern jacobian_pattern(JacobianEntries entries = JacobianEntries::all) const;
  // The derivatives that read at least `min_sources` outputs through one fan-in input.
  std::vector<FanInRow> fan_in_rows(int min_sources) const;
  // d f_row / d signal at (time, state) by central differences of the row's component alone
  // (its outputs and derivatives with that one signal moved by +-step). The context's signals
  // must hold the outputs at (time, state); they do again afterwards. `scratch` holds
  // state_size() derivatives.
  double row_sensitivity(Context& context, double time, double signal_time, const double* state,
                         const FanInRow& row, int signal, double step, double* scratch) const;

 private:
  friend class SystemBuilder;
  System() = default;
  Evaluation evaluation(Context& context, double time, double signal_time,
                        const double* state) const;
  std::vector<std::vector<int>> signal_state_dependencies(
      JacobianEntries entries = JacobianEntries::all) const;
  std::set<int> derivative_columns(const std::vector<std::vector<int>>& signal_states,
                                   std::size_t component, int state, int skipped_input,
                                   JacobianEntries entries = JacobianEntries::all) const;
  // Whether `entries` reads input `input` of component `component`.
  bool reads_input(std::size_t component, int input, JacobianEntries entries) const;
  void assign_slices(const SystemBuilder& builder);
  void wire(const SystemBuilder& builder);
  void order_by_feedthrough(const SystemBuilder& builder);
  void collect_parameters(const SystemBuilder& builder);
  RunSetup setup_of(const Context& context, std::size_t component) const;
  void rebuild_signals(Context& context) const;
  void check_run_parameters(const Context& context) const;

  std::vector<std::unique_ptr<Component>> components_;
  std::vector<std::vector<InputDeclaration>> inputs_;  // per component, as declared
  std::vector<int> state_counts_;                      // per component
  std::vector<int> parameter_counts_;                  // per component
  std::vector<Component*> evaluation_order_;
  std::vector<Component*> sampling_order_;
  std::vector<int> event_offsets_;  // per component
  int event_count_ = 0;
  std::vector<StateInfo> states_;
  std::vector<ChannelInfo> channels_;
  std::unordered_map<std::string, int> channel_by_name_;  // "group.name" -> channel
  std::vector<int> signal_owner_;                         // component index that writes each signal
  std::vector<ParameterInfo> parameters_;
  std::unordered_map<std::string, int> parameter_by_path_;
  std::vector<SignalSlot> signal_slots_;
  std::unordered_map<std::string, int> slot_by_name_;  // "group.name" -> slot
  struct Derivation {
    int parameter;
    ParameterRule rule;
  };
  std::vector<Derivation> derivations_;
  std::vector<ParameterConstraint> constraints_;
  std::vector<MemberSet> member_sets_;
  std::vector<ExternalInputInfo> external_inputs_;
};

// A System that does not assemble, with the origins (SystemBuilder::set_origin) of what caused
// it, where it should be reported first: the connections that gave an input a source too many,
// the component whose input has none or that duplicates another's name. Empty: none known.
class AssemblyError : public std::logic_error {
 public:
  AssemblyError(const std::string& what, std::vector<int> origins)
      : std::logic_error(what), origins_(std::move(origins)) {}
  const std::vector<int>& origins() const { return origins_; }

 private:
  std::vector<int> origins_;
};

// Builds a System: components are added, wired by name and assembled once.
class SystemBuilder {
 public:
  template <typename T>
  T& add(std::unique_ptr<T> component) {
    T& reference = *component;
    component_origins_[&reference] = origin_;
    components_.push_back(std::move(component));
    return reference;
  }
  // What is added and connected from now on comes from `origin`, the caller's index of its
  // source (the scenario section being built; -1: none), for AssemblyError to name.
  void set_origin(int origin) { origin_ = origin; }

  // Connects `consumer`'s input `input_name` to the output "group.name". A fan-in input may be
  // connected to several outputs, in order.
  void connect(const Component& consumer, std::string_view input_name,
               std::string_view source_output);
  // Names a component's input as a port of its instance ("left.power"), so that whoever
  // drives the instance need not know its parts.
  void export_input(std::string_view port, const Component& consumer, std::string_view input_name);
  // Makes `consumer`'s input read whatever is connected to an exported port as well (an effect
  // attached to a muscle reading the muscle's power). Exported or not, the port must be
  // connected before the System is built.
  void share_input(std::string_view port, const Component& consumer, std::string_view input_name);
  // Connects an exported port to the output "group.name".
  void connect(std::string_view port, std::string_view source_output);
  // Whether anything has been connected to an exported port.
  bool is_connected(std::string_view port) const;

  // Makes the parameter `path` follow `rule`, evaluated when a run starts; `explanation` says
  // from what ("1 / drive.pwm_frequency").
  void derive(std::string path, ParameterRule rule, std::string explanation);
  void constrain(ParameterConstraint constraint);
  // Whether a component added so far declares the parameter `path`.
  bool declares_parameter(std::string_view path) const;
  // Declares the instances "<set.name>/<member>" alike, to be recorded together (MemberSet).
  void declare_members(MemberSet set);

  // Resolves offsets and connections and fixes the evaluation order. Throws AssemblyError on an
  // unconnected input, an unknown output, a duplicate output, state or parameter, or an
  // algebraic loop. The builder is empty afterwards.
  std::shared_ptr<const System> build();

 private:
  friend class System;
  struct Connection {
    const Component* consumer;
    std::string input;
    std::string source;
    int origin;
  };
  struct PortConnection {
    std::string port;
    std::string source;
    int origin;
  };
  int origin_of(const Component& component) const;
  struct Export {
    const Component* consumer;
    std::string input;
  };
  std::vector<std::unique_ptr<Component>> components_;
  std::vector<Connection> connections_;
  std::unordered_map<std::string, Export> ports_;
  std::unordered_multimap<std::string, Export> shared_ports_;
  std::vector<PortConnection> port_connections_;
  int origin_ = -1;
  std::unordered_map<const Component*, int> component_origins_;
  struct PendingDerivation {
    std::string path;
    ParameterRule rule;
    std::string explanation;
  };
  std::vector<PendingDerivation> derivations_;
  std::vector<ParameterConstraint> constraints_;
  std::vector<MemberSet> member_sets_;
};

}  // namespace tcpmsim
