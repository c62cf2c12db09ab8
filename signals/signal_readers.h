#pragma once

#include <memory>
#include <string_view>

#include "sim/config/config_node.h"
#include "sim/signal.h"
#include "sim/signal_reading.h"

// How each signal kind reads its section (values in `si_unit`). Every signal read here carries
// a recipe: its values (levels, times, bands, amplitudes) are parameters a run context may
// change (see sim/signal.h); its counts (components, steps, frequencies), switches and drawn
// random phases are part of its structure. The kinds
// are registered by name in signals/signal_kinds.h.
namespace tcpmsim::signal_readers {

// A bare quantity, or {type: constant, value: ...}.
std::unique_ptr<Signal> constant(const ConfigNode& node, std::string_view si_unit,
                                 const SignalContext& context);
std::unique_ptr<Signal> steps(const ConfigNode& node, std::string_view si_unit,
                              const SignalContext& context);
std::unique_ptr<Signal> ramp(const ConfigNode& node, std::string_view si_unit,
                             const SignalContext& context);
std::unique_ptr<Signal> piecewise_linear(const ConfigNode& node, std::string_view si_unit,
                                         const SignalContext& context);
std::unique_ptr<Signal> staircase(const ConfigNode& node, std::string_view si_unit,
                                  const SignalContext& context);
std::unique_ptr<Signal> sine(const ConfigNode& node, std::string_view si_unit,
                             const SignalContext& context);
std::unique_ptr<Signal> multisine(const ConfigNode& node, std::string_view si_unit,
                                  const SignalContext& context);
std::unique_ptr<Signal> random_steps(const ConfigNode& node, std::string_view si_unit,
                                     const SignalContext& context);
std::unique_ptr<Signal> log_sweep(const ConfigNode& node, std::string_view si_unit,
                                  const SignalContext& context);
std::unique_ptr<Signal> sequence(const ConfigNode& node, std::string_view si_unit,
                                 const SignalContext& context);
std::unique_ptr<Signal> periodic(const ConfigNode& node, std::string_view si_unit,
                                 const SignalContext& context);
std::unique_ptr<Signal> stepped_sine_sweep(const ConfigNode& node, std::string_view si_unit,
                                           const SignalContext& context);
std::unique_ptr<Signal> step_sequence(const ConfigNode& node, std::string_view si_unit,
                                      const SignalContext& context);

}  // namespace tcpmsim::signal_readers
