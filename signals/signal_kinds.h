#pragma once

#include "sim/registry.h"

namespace tcpmsim {

// Registers the category "signal" and every signal kind: constant (also a bare quantity),
// steps, ramp, piecewise_linear, staircase, sine, multisine, random_steps, log_sweep, sequence,
// periodic, stepped_sine_sweep, step_sequence.
void register_signal_kinds(KindRegistry& kinds);

}  // namespace tcpmsim
