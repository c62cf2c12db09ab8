#pragma once

#include <span>
#include <vector>

// Where a model and a measurement disagree, read from the residuals (measured - simulated) of
// a fit on a validation window: are they white, do they follow an input, in which band is their
// power, do they drift. The diagnostics of `tcpmsim discover` (issue 12), each a pure function.
namespace tcpmsim::fit {

// Sample autocorrelation r_k, k = 0..lags (r_0 = 1), of the mean-removed series.
std::vector<double> autocorrelation(std::span<const double> series, int lags);

// The Ljung-Box portmanteau test of whiteness: Q = n (n + 2) sum_k r_k^2 / (n - k) over
// k = 1..lags, chi-squared with `lags` degrees of freedom for white noise; a small p-value
// says the residuals hold structure the model missed.
struct LjungBox {
  int lags = 0;
  double statistic = 0.0;
  double p_value = 1.0;
};
LjungBox ljung_box(std::span<const double> series, int lags);

// The normalised cross-correlation c(l) = sum_t x(t) y(t + l) / (n s_x s_y) of two mean-removed
// series at lags -max_lag..max_lag (y lags x by l > 0). For independent white series |c| stays
// within bound = 1.96 / sqrt(n) at 95 %.
struct CrossCorrelation {
  int max_lag = 0;
  std::vector<double> values;  // at lags -max_lag..max_lag
  double bound = 0.0;
  int peak_lag = 0;  // where |c| is largest
  double peak = 0.0;
};
CrossCorrelation cross_correlation(std::span<const double> x, std::span<const double> y,
                                   int max_lag);

// The share of the series' variance in each frequency band [lower, upper) [Hz], from its
// periodogram (sample interval dt); bands need not cover all frequencies.
std::vector<double> band_power(std::span<const double> series, double dt,
                               std::span<const std::pair<double, double>> bands);

// A straight line through the series against time: the slope, its standard error, and the
// t-statistic slope / error (|t| > 3: a drift).
struct Drift {
  double slope = 0.0;
  double standard_error = 0.0;
  double t_statistic = 0.0;
};
Drift drift(std::span<const double> time, std::span<const double> series);

// The Pearson correlation of two series of one length (0 when either is constant).
double correlation(std::span<const double> x, std::span<const double> y);

// The loop a residual force r draws against a deflection x, band by band: from the cross-
// spectrum of the two, the part of r in quadrature with x per unit x, q = Im(S_xr) / S_xx [unit
// of r per unit of x], in each band [lower, upper) where x has power. Energy lost per cycle of
// amplitude a is pi q a^2: a rate-independent loop (hysteresis) keeps q flat over frequency, a
// viscous one grows it as f (q = 2 pi f c). `exponent` is the slope of ln|q| against ln f over
// the bands, NaN with fewer than two.
struct LoopSpectrum {
  std::vector<double> frequency;  // each band's geometric centre [Hz]
  std::vector<double> quadrature;
  double exponent = 0.0;
};
LoopSpectrum loop_spectrum(std::span<const double> deflection, std::span<const double> residual,
                           double dt, std::span<const std::pair<double, double>> bands);

}  // namespace tcpmsim::fit
