#pragma once

#include <vector>

namespace tcpmsim::fit {

// The standard deviation of a measured series' noise, from the data alone: the RMS of its third
// differences y[i+3] - 3 y[i+2] + 3 y[i+1] - y[i], which hold 20 times the variance of white
// noise and next to nothing of a signal that is smooth over four samples (a polynomial of
// degree two cancels exactly; a 0.1 Hz sine at 16 Hz keeps 1e-4 of its amplitude), over those
// within 4.5 robust deviations (from their median): a step, which spoils a few, is cut. Coloured
// noise that the sampling resolves (an instrument's own low-pass) is underestimated: give the floor
// instead
// (`discover --noise`). Data on a grid carry at least its rounding error, step / sqrt(12), with
// the smallest change between samples taken as the step. NaN for fewer than 8 samples.
// `steps` marks the samples at or next to a jump of a replayed input (steps_in_inputs), whose
// differences hold the output's true response and are left out; empty: none.
double difference_noise_floor(const std::vector<double>& values,
                              const std::vector<char>& steps = {});

// The least change of a replayed input that counts as its own jump or one-sample excursion: 2 %
// of its range. A replayed input is often noise-free (held between steps, or on a grid), so a
// noise scale says nothing about it, and a multisine's smooth peaks stay below this.
double input_jump_threshold(const std::vector<double>& input);

// Per sample, whether a third difference that spans it meets a jump of one of `inputs` above
// its input_jump_threshold: a deflection step moves a muscle's force at once.
std::vector<char> steps_in_inputs(const std::vector<const std::vector<double>*>& inputs,
                                  std::size_t samples);

}  // namespace tcpmsim::fit
