#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <vector>

#include "analysis/frequency_response.h"
#include "analysis/step_response.h"
#include "signals/control_task_signals.h"

namespace tcpmsim {

// Analysis of the thesis' control tasks (sections 7.3.4, 7.3.6, 7.4) over sampled time series:
// time t (increasing), the reference r as the controller used it, the true response y (load
// cell, encoder) and the estimate y^. The references themselves are built by
// signals/control_task_signals.h; their step and frequency-response measures are
// analysis/step_response.h and analysis/frequency_response.h, which `tcpmsim analyze` applies to
// any record.

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
