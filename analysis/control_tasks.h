#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <vector>

#include "signals/control_task_signals.h"

namespace tcpmsim {

// Analysis of the thesis' control tasks (sections 7.3.4, 7.3.6, 7.4) over sampled time series:
// time t (increasing), the reference r as the controller used it, the true response y (load
// cell, encoder) and the estimate y^. The references themselves are built by
// signals/control_task_signals.h.

// ---- Rise times of a step sequence --------------------------------------------------------

// Rise time of one step: from the instant the response first reaches y0 + lower (r - y0) to the
// instant it first reaches y0 + upper (r - y0), where y0 is the response at the step and r the
// new reference; crossings are interpolated linearly between samples. The default 10 %-90 %
// gives tau ln 9 for a first-order response. lower = 0 measures from the step itself, and
// {0, 1} is "time until the response reaches the reference".
//
// A step whose response does not reach the upper level before the next step (or the end of the
// data) is reported with rise_time equal to its hold, the time it was given, and reached =
// false. That is how the thesis' outliers "at 20 s" arise: a response that never got there is
// charged the whole 20 s hold, independent of where its lower crossing was.
struct RiseTimeDefinition {
  double lower = 0.1;  // fractions of the step, 0 <= lower < upper <= 1
  double upper = 0.9;
};

struct StepRise {
  std::size_t index = 0;    // the first sample carrying the new reference
  double step_time = 0.0;   // t at that sample [s]
  double hold = 0.0;        // until the next step; the last until one sample past the end
  double start = 0.0;       // y0, the response at the step
  double target = 0.0;      // the new reference
  double lower_time = 0.0;  // when the lower level was reached [s]; NaN if never
  double upper_time = 0.0;  // when the upper level was reached [s]; NaN if never
  double rise_time = 0.0;   // upper_time - lower_time, or `hold` if not reached [s]
  bool reached = false;
};

// A step is any change of the reference between consecutive samples by more than `threshold`
// (give the step task's stretch of the record, not the sweep). The step instant is the first
// sample with the new value: put samples on the step instants (the control-task steps fall on
// the controller's 20 Hz grid) or accept up to one sample interval of timing error.
std::vector<StepRise> step_rise_times(std::span<const double> time,
                                      std::span<const double> reference,
                                      std::span<const double> response,
                                      const RiseTimeDefinition& definition = {},
                                      double threshold = 0.0);

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

// ---- Estimation error (7.3.6, 7.4) --------------------------------------------------------

// error = estimate - truth (the thesis' mean deflection error -0.27 mm is an underestimate).
// The thesis' "95 % confidence interval" of +-2.14 mm around the mean error is the band that
// holds 95 % of the errors (its Fig. 7.6 draws it around the samples), not a confidence
// interval of the mean (with thousands of samples that would be a few hundredths of a mm).
// half_width_95 is z_0.975 s = 1.959964 s with s the sample standard deviation (n - 1): the
// symmetric "mean +- half width" form the thesis prints, exact for Gaussian errors. The
// empirical 2.5 % and 97.5 % percentiles (linear interpolation between order statistics,
// NumPy's default) are given too: they show when the errors are skewed or heavy-tailed, as
// spikes make them.
struct ErrorStatistics {
  std::size_t count = 0;
  double mean = 0.0;
  double standard_deviation = 0.0;
  double half_width_95 = 0.0;
  double percentile_2_5 = 0.0;
  double percentile_97_5 = 0.0;
  double rmse = 0.0;
};
ErrorStatistics error_statistics(std::span<const double> errors);
// Of the errors estimate - truth.
ErrorStatistics estimation_error_statistics(std::span<const double> truth,
                                            std::span<const double> estimate);

// The calibration offset of section 7.3.4: mean(truth - estimate) over the calibration window,
// to be added to the estimator's current offset.
double calibration_offset(std::span<const double> truth, std::span<const double> estimate);

}  // namespace tcpmsim
