#pragma once

#include <optional>

// What counts as one instant, shared by the integrator and every component that keeps time
// itself (sample instants, PWM edges, reference steps), so that they all agree.
namespace tcpmsim {

// Times closer than this are one instant. The integrator merges a breakpoint within
// 2 time_margin(t) after the instant t into t: it is never delivered on its own.
double time_margin(double t);
bool same_instant(double t, double instant);

// The sample grid k * period from t = 0. Instants are computed by multiplication, never by
// accumulation, so they do not drift over a long run.
// k, if t is the instant k * period.
std::optional<long> grid_index_at(double t, double period);
// The first instant k * period after t.
double next_grid_instant(double t, double period);

}  // namespace tcpmsim
