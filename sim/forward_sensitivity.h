#pragma once

#include <span>
#include <string>
#include <vector>

#include "sim/context.h"
#include "sim/system.h"

namespace tcpmsim {

// Forward sensitivities of a run to some of its parameters. The sensitivity s_j = dy/dp_j of the
// state obeys
//     s_j' = (df/dy) s_j + df/dp_j,     s_j(t0) = dy(t0)/dp_j,
// which CVODES integrates beside the state, under the same error control (staggered corrector).
//
// Components turn their parameters into run state when a run starts, so df/dp_j cannot come
// from CVODES perturbing an array it holds. Each parameter has instead two contexts of its own,
// at p_j + h and p_j - h, prepared once; both terms then come from one central directional
// difference (CVODES' own simultaneous quotient, with the parameter step held fixed):
//     s_j' = [f(y + h s_j; p + h e_j) - f(y - h s_j; p - h e_j)] / (2 h).
// An output's sensitivity dg/dp_j comes the same way from the outputs. Where p_j - h is outside
// the parameter's range the difference is one-sided, from p_j.
//
// What sensitivities cannot follow: a component that changes its run state at breakpoints or
// events (a sampled controller), zero-crossing events, and the Adams method.
class ForwardSensitivities {
 public:
  // `parameters`: indices into the system's parameters; `scales`: their typical magnitudes
  // (SI), which set the difference steps (h_j = relative_step * scale_j) and CVODES' scaling
  // of the sensitivities' error weights. The contexts are copies of `base` with one parameter
  // moved. Throws std::invalid_argument when the system does not allow sensitivities, and
  // ParameterError when a parameter cannot move either way.
  ForwardSensitivities(const Context& base, std::vector<int> parameters, std::vector<double> scales,
                       double relative_step = 1e-4);

  // Why the system does not allow forward sensitivities, or "".
  static std::string unsupported_reason(const System& system);

  int count() const { return static_cast<int>(parameters_.size()); }
  const std::vector<double>& scales() const { return scales_; }

  // s_j(t0) for every j from the initial states of the moved contexts; makes every context ready
  // and lets its sampled parts take their first sample, as the base run does.
  void initialize(double t0, std::span<double* const> sensitivities);
  // s_j' at (t, y) for the sensitivity s_j. Allocation-free.
  void derivatives(int j, double t, double signal_time, const double* state,
                   const double* sensitivity, double* result);
  // dg/dp_j of every output at (t, y): afterwards output_sensitivity(j) holds it.
  void outputs(int j, double t, double signal_time, const double* state, const double* sensitivity);
  std::span<const double> output_sensitivity(int j) const {
    return output_sensitivities_[static_cast<std::size_t>(j)];
  }
  // Throws std::invalid_argument when a tracked parameter moves the discontinuity after `time`
  // away from `next` (the base run's): the sensitivity would jump there, which is not followed.
  void check_breakpoint(double time, double next);
  // Lets the moved contexts pass a breakpoint as the base context does.
  void at_breakpoint(double time, double left_limit, const double* state,
                     std::span<const double* const> sensitivities);

 private:
  // One side of a difference: a context with the parameter moved by `shift`.
  struct Side {
    Context context;
    double shift;
  };
  struct Moved {
    std::vector<Side> sides;  // high, then low
    double span;              // high.shift - low.shift
  };
  // y + shift s into moved_state_.
  const double* moved_state(const double* state, const double* sensitivity, double shift);

  const System& system_;
  std::vector<int> parameters_;
  std::vector<double> scales_;
  std::vector<Moved> moved_;
  std::vector<double> moved_state_, high_, low_;
  std::vector<std::vector<double>> output_sensitivities_;
};

}  // namespace tcpmsim
