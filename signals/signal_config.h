#pragma once

#include <cstdint>
#include <memory>
#include <string_view>

#include "sim/config/config_node.h"
#include "sim/signal.h"

namespace tcpmsim {

struct SignalContext {
  std::uint64_t seed = 0;  // the scenario seed; each random signal draws its own stream
  double duration = 0.0;   // the time the signal is meant to cover [s]
};

// Reads a signal whose values are in `si_unit`. A bare quantity is a constant; otherwise
// `type` is one of constant, steps, ramp, piecewise_linear, staircase, sine, multisine,
// random_steps, log_sweep, sequence, periodic.
std::unique_ptr<Signal> read_signal(const ConfigNode& node, std::string_view si_unit,
                                    const SignalContext& context);

}  // namespace tcpmsim
