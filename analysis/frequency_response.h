#pragma once

#include <complex>
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "signals/control_task_signals.h"

// Frequency responses from sampled series: the thesis' stepped-sine sweep (7.3.6) and its -3 dB
// bandwidth, and the estimates `tcpmsim analyze` makes from any excited record.
namespace tcpmsim {

// ---- Sine fits and frequency response (7.3.6) ---------------------------------------------

// Least squares fit y ~ offset + amplitude sin(2 pi f (t - origin) + phase) at a given
// frequency over the samples with begin <= t < end. amplitude >= 0, phase in (-pi, pi].
struct SineFit {
  double frequency = 0.0;  // [Hz]
  double amplitude = 0.0;
  double phase = 0.0;  // [rad], relative to sin(2 pi f (t - origin))
  double offset = 0.0;
  double rms_residual = 0.0;
  std::size_t samples = 0;
};
SineFit fit_sine(std::span<const double> time, std::span<const double> values, double frequency,
                 double origin, double begin, double end);

struct FrequencyResponsePoint {
  double frequency = 0.0;     // [Hz]
  double magnitude = 0.0;     // response amplitude / reference amplitude
  double magnitude_db = 0.0;  // 20 log10(magnitude)
  double phase = 0.0;         // response phase - reference phase [rad], unwrapped over the sweep
  SineFit reference;
  SineFit response;
};

// For each frequency of the sweep, fits reference and response over the last `fit_periods`
// periods of that frequency (the thesis: the last two of three, after the transient of the
// frequency change) and compares them. The phase is wrapped to (-pi, pi] at the first
// frequency and unwrapped from there (each next value within pi of the previous), so a lag
// growing past 180 degrees stays continuous.
std::vector<FrequencyResponsePoint> sweep_frequency_response(std::span<const double> time,
                                                             std::span<const double> reference,
                                                             std::span<const double> response,
                                                             const SweepSchedule& schedule,
                                                             double fit_periods = 2.0);

// The -3 dB bandwidth (7.3.6): the first frequency, scanning up, at which the magnitude falls to
// 20 log10(1/sqrt 2) = -3.0103 dB (half power, so that a first-order lag 1/(1 + s tau) gives
// 1/(2 pi tau)), interpolated linearly between the two measured points that bracket it, in dB
// against log10(f): the straight segments between the markers of the thesis' Bode plot (Fig.
// 7.8). The points must be in increasing frequency. nullopt when no crossing is bracketed (the
// first point already below, or none below).
std::optional<double> bandwidth_3db(std::span<const FrequencyResponsePoint> points);

// ---- Estimates from any excited record ------------------------------------------------------

// One input of an estimate: its recorded series over the window and, for a multisine, the
// frequencies it excites there (empty: a broadband input, random steps or noise).
struct ExcitedInput {
  std::string name;  // "drive/power"
  std::span<const double> values;
  std::vector<double> lines;  // [Hz]
};

// H(f) of the output against one input, with its 95 % confidence region: H lies within
// `radius_95` of the estimate (a circle in the complex plane), so |H| within
// |H| +- radius_95 and the phase within +- asin(radius_95 / |H|).
struct ResponseEstimate {
  double frequency = 0.0;  // [Hz]
  std::complex<double> response;
  double magnitude = 0.0;
  double magnitude_db = 0.0;
  double phase = 0.0;  // [rad], unwrapped along the frequencies
  double radius_95 = 0.0;
  double coherence = 0.0;  // spectral: the multiple coherence; lines: 1 - noise / total power
  std::string overlap;     // a line another input excites too (within the resolution): not
                           // estimable from this record; response and radius are NaN
};

// At the excited lines (the inputs are multisines): one least-squares fit of a constant and a
// sine and cosine at every line of every input, to the output and to each input, over the
// window (time and the series, the transient already left out). H at a line of input j is
// Y(f) / U_j(f); lines of different inputs closer than a twentieth of the resolution
// 1 / (window length) are the same line, flagged as overlapping (closer lines than the
// resolution are still fitted apart, their covariance widening the band). The confidence radius
// propagates the residual variance of the output's and the input's fits (their covariance (A^T
// A)^-1 s^2) through Y / U: a complex Gaussian's 95 % circle, sqrt(chi2_2(0.95)) = 2.4477 standard
// deviations. Returns one list per input, in the inputs' order.
std::vector<std::vector<ResponseEstimate>> line_response(std::span<const double> time,
                                                         std::span<const ExcitedInput> inputs,
                                                         std::span<const double> output);

// By spectral estimation, for broadband inputs: Welch's averaged periodograms (Hann window,
// half-overlapping segments of `segment_samples` samples) of the series' first differences (a
// filter applied to input and output alike leaves H unchanged; it whitens steps and random
// steps, whose steep spectra would otherwise leak from the low bins into the rest), each
// segment's mean removed, and the H1 estimate H = S_yu S_uu^-1, a row per frequency over all
// inputs at once (the multi-input estimate: inputs excited together are told apart by their
// cross-spectra). Coherence is the multiple coherence S_yu S_uu^-1 S_uy / S_yy. The confidence
// radius is the jackknife's: H recomputed without each segment in turn, the spread of those
// estimates its variance (Thomson and Chave 1991), which holds for non-Gaussian inputs and
// counts the segments' leakage and boundary transients, where the coherence formula counts only
// noise. Kept are the frequencies an input excites (its differenced auto-spectrum at least 1 %
// of its peak) where H stands out of its confidence region (|H| >= 2 radius_95), from the second
// bin on (the lowest lies in the window's main lobe about DC, which the mean's removal
// distorts). Needs at least q + 2 segments. Returns one list per input.
std::vector<std::vector<ResponseEstimate>> spectral_response(std::span<const double> time,
                                                             std::span<const ExcitedInput> inputs,
                                                             std::span<const double> output,
                                                             std::size_t segment_samples);

// The -3 dB bandwidth of an estimate (bandwidth_3db), its magnitude taken relative to
// `reference_magnitude` (1 for a closed loop whose output tracks its input; the lowest
// frequency's magnitude for a plant whose units differ). Estimates without a value are skipped.
std::optional<double> estimate_bandwidth_3db(std::span<const ResponseEstimate> estimates,
                                             double reference_magnitude);

}  // namespace tcpmsim
