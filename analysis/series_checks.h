#pragma once

#include <cstddef>
#include <span>

// The checks every analysis of sampled series makes on its input, with messages naming the
// analysis (`what`) and the series; failures are std::invalid_argument.
namespace tcpmsim {

void require_finite(std::span<const double> values, const char* what, const char* name);
void require_same_length(std::size_t a, std::size_t b, const char* what);
// Finite and strictly increasing.
void require_time(std::span<const double> time, const char* what);
// An angle to (-pi, pi].
double wrap_phase(double phase);

}  // namespace tcpmsim
