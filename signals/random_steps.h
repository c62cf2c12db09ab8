#pragma once

#include <memory>

#include "signals/piecewise_constant_signal.h"
#include "sim/random_stream.h"

namespace tcpmsim {

// Random steps after generalised binary noise (7.13)-(7.14), as the thesis builds them.
// At every sample instant k / f_s the signal switches with probability 1 / (0.5 tau_p f_s),
// so the mean time between switches is tau_p / 2. (The printed (7.14) gives the probability
// of *not* switching.) A step has a size uniform in [0, max_step_fraction (high - low)] and a
// random direction, reversed if it would leave [low, high]. The realisation is finally scaled
// to span [low, high] exactly.
struct RandomStepsSettings {
  double low = 0.0;
  double high = 1.0;
  double process_time_constant = 1.0;  // tau_p [s]
  double sample_rate = 1.0;            // f_s [Hz]
  double max_step_fraction = 0.25;
  double duration = 1.0;
  bool scale_to_range = true;
};

double switching_probability(const RandomStepsSettings& settings);

std::unique_ptr<PiecewiseConstantSignal> make_random_steps(const RandomStepsSettings& settings,
                                                           RandomStream& stream);

}  // namespace tcpmsim
