#pragma once

#include <cstddef>
#include <string>

#include "sweep/sweep_spec.h"

namespace tcpmsim::sweep {

// The summary of the sweep `spec` written to `output`, as a table for the terminal: a row per run
// (the first and the last `rows` / 2 of a longer sweep, with how many are left out between), a
// column per axis, derived parameter and metric headed by its name and SI unit, then the status.
// Numbers to 6 significant digits; a metric a run could not give is "nan".
std::string sweep_table(const SweepSpec& spec, const std::string& output, std::size_t rows = 20);

}  // namespace tcpmsim::sweep
