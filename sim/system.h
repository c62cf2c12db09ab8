#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "sim/component.h"
#include "sim/sparsity.h"

namespace tcpmsim {

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
};

// Assembles components into one ODE system y' = f(t, y). Owns the components, assigns each its
// slice of the state vector and of the signal (output) vector, wires inputs to outputs and
// evaluates everything in an order that respects direct feedthrough.
class System {
 public:
  System() = default;
  System(const System&) = delete;
  System& operator=(const System&) = delete;

  template <typename T>
  T& add(std::unique_ptr<T> component) {
    T& reference = *component;
    components_.push_back(std::move(component));
    return reference;
  }

  // Connects `consumer`'s input `input_name` to the output "group.name".
  void connect(const Component& consumer, std::string_view input_name,
               std::string_view source_output);

  // Resolves offsets and connections and fixes the evaluation order. Throws std::logic_error on
  // an unconnected input, an unknown output, a duplicate output or an algebraic loop.
  void assemble();

  int state_size() const { return state_size_; }
  int signal_size() const { return static_cast<int>(signals_.size()); }
  const std::vector<StateInfo>& states() const { return states_; }
  const std::vector<ChannelInfo>& channels() const { return channels_; }
  const std::vector<std::unique_ptr<Component>>& components() const { return components_; }
  int signal_index(std::string_view output) const;  // -1 if absent

  // The first component of type T, or nullptr. Like components(), it hands out the components
  // themselves: an analysis calibrates an estimator between runs through it.
  template <typename T>
  T* find() const {
    for (const auto& component : components_) {
      if (auto* found = dynamic_cast<T*>(component.get())) return found;
    }
    return nullptr;
  }

  void initialize(double time, double* state);
  // Computes every output, observed ones included; afterwards signals() holds them.
  void evaluate_outputs(double time, double signal_time, const double* state);
  // f(t, y). Allocation-free.
  void evaluate_derivatives(double time, double signal_time, const double* state,
                            double* derivatives);
  const std::vector<double>& signals() const { return signals_; }

  double next_breakpoint_after(double time) const;
  // Lets sampled components act at a breakpoint. Outputs are recomputed with signals sampled
  // at `left_limit` (just before the instant) first, so a controller samples what was true
  // just before it acts.
  void at_breakpoint(double time, double left_limit, const double* state);

  // Lets components adapt per-state tolerances; both arrays hold the configured ones on entry.
  void adapt_tolerances(double* absolute, double* relative) const;

  // Events: all components' zero-crossing functions, concatenated.
  int event_count() const { return event_count_; }
  std::vector<int> event_directions() const;
  void evaluate_events(double time, double signal_time, const double* state, double* values);
  // Tells the owners of the crossed events (flags[k] != 0) where they are.
  void at_events(double time, double signal_time, const double* state, const int* flags);

  // Self-check for tests: every component, evaluated at (time, state), writes exactly its own
  // outputs and derivatives and nothing else. Returns a description of the first violation,
  // or an empty string.
  std::string check_component_contracts(double time, const double* state);

  // Structural non-zeros of df/dy (row = derivative, column = state).
  SparsityPattern jacobian_pattern() const;

 private:
  struct Connection {
    const Component* consumer;
    std::string input;
    std::string source;
  };
  Evaluation evaluation(double time, double signal_time, const double* state);
  void order_by_feedthrough();

  std::vector<std::unique_ptr<Component>> components_;
  std::vector<Component*> evaluation_order_;
  std::vector<Component*> sampling_order_;
  std::vector<int> event_offsets_;  // per component, in components_ order
  std::vector<int> state_counts_;   // per component, in components_ order
  int event_count_ = 0;
  std::vector<Connection> connections_;
  std::vector<StateInfo> states_;
  std::vector<ChannelInfo> channels_;
  std::vector<int> signal_owner_;  // component index that writes each signal
  std::vector<double> signals_;
  int state_size_ = 0;
  bool assembled_ = false;
};

}  // namespace tcpmsim
