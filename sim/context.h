#pragma once

#include <memory>
#include <span>
#include <string_view>
#include <vector>

#include "sim/component.h"
#include "sim/signal.h"
#include "sim/system.h"

namespace tcpmsim {

// Everything one run of a System changes, kept apart from the immutable System (as Drake's
// Context): the parameter values, the continuous state, the outputs, each component's run
// state (discrete state, held values, filter buffers, random streams, scratch) and the signals
// as this run's parameters make them. One System serves any number of contexts, on any number
// of threads; a context is used by one thread at a time.
//
// Parameters are set by path in SI ("muscle.mechanics.k2", 3.0 for 3 N/m), checked against
// their declared range at once and against the conditions between them when a run starts; no
// scenario file is read again and no unit is parsed.
class Context {
 public:
  explicit Context(const System& system);
  // Another context of the same system with the same parameter values; its run state is made
  // afresh when its run starts.
  Context(const Context& other);
  Context& operator=(const Context&) = delete;
  Context(Context&&) noexcept = default;

  const System& system() const { return *system_; }

  double parameter(std::string_view path) const;
  double parameter(int index) const { return parameters_[static_cast<std::size_t>(index)]; }
  // Throws ParameterError for an unknown path, a derived parameter or a value outside the
  // parameter's range.
  void set_parameter(std::string_view path, double value);
  void set_parameter(int index, double value);
  // Whether any parameter differs from the value the model was built with.
  bool parameters_changed() const;

  // The continuous state (after a run: its final state), the outputs of the latest evaluation,
  // and a prescribed signal: as built until System::prepare, then as this run's parameters
  // make it.
  std::vector<double>& state() { return state_; }
  const std::vector<double>& state() const { return state_; }
  const std::vector<double>& signals() const { return signals_; }
  const Signal& signal(int slot) const { return *prescribed_[static_cast<std::size_t>(slot)]; }
  // A component's run state, for inspection after or during a run (tests, analyses).
  template <typename T>
  const T& run_state(const Component& component) const {
    return static_cast<const T&>(*run_states_[static_cast<std::size_t>(component.index_)]);
  }

 private:
  friend class System;
  const System* system_;
  std::vector<double> parameters_;
  std::vector<double> signals_;
  std::vector<double> state_;
  std::vector<std::unique_ptr<RunState>> run_states_;
  std::vector<const Signal*> prescribed_;
  std::vector<std::unique_ptr<Signal>> rebuilt_signals_;
  // Prepared for a run not yet started (System::initialize then skips preparing again).
  bool prepared_ = false;
};

}  // namespace tcpmsim
