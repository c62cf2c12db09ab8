#include "identification/residual_diagnostics.h"

#include <boost/math/distributions/chi_squared.hpp>
#include <unsupported/Eigen/FFT>

#include <cmath>
#include <complex>
#include <limits>
#include <numeric>
#include <stdexcept>

namespace tcpmsim::fit {

namespace {

std::vector<double> centred(std::span<const double> series) {
  if (series.size() < 2) throw std::invalid_argument("a diagnostic needs at least two samples");
  const double mean =
      std::accumulate(series.begin(), series.end(), 0.0) / static_cast<double>(series.size());
  std::vector<double> values(series.begin(), series.end());
  for (double& value : values) value -= mean;
  return values;
}

double sum_of_squares(const std::vector<double>& values) {
  return std::inner_product(values.begin(), values.end(), values.begin(), 0.0);
}

}  // namespace

std::vector<double> autocorrelation(std::span<const double> series, int lags) {
  const std::vector<double> x = centred(series);
  const double variance = sum_of_squares(x);
  const auto n = x.size();
  std::vector<double> r(static_cast<std::size_t>(lags) + 1, 0.0);
  for (std::size_t k = 0; k < r.size() && k < n; ++k) {
    double sum = 0.0;
    for (std::size_t t = 0; t + k < n; ++t) sum += x[t] * x[t + k];
    r[k] = variance > 0 ? sum / variance : 0.0;
  }
  return r;
}

LjungBox ljung_box(std::span<const double> series, int lags) {
  const auto n = static_cast<double>(series.size());
  if (lags < 1 || lags >= static_cast<int>(series.size()))
    throw std::invalid_argument("Ljung-Box: need 1 <= lags < samples");
  const std::vector<double> r = autocorrelation(series, lags);
  LjungBox test;
  test.lags = lags;
  for (int k = 1; k <= lags; ++k)
    test.statistic += r[static_cast<std::size_t>(k)] * r[static_cast<std::size_t>(k)] / (n - k);
  test.statistic *= n * (n + 2.0);
  const boost::math::chi_squared distribution(lags);
  test.p_value = boost::math::cdf(boost::math::complement(distribution, test.statistic));
  return test;
}

CrossCorrelation cross_correlation(std::span<const double> x_series,
                                   std::span<const double> y_series, int max_lag) {
  if (x_series.size() != y_series.size())
    throw std::invalid_argument("cross-correlation: the series differ in length");
  const std::vector<double> x = centred(x_series);
  const std::vector<double> y = centred(y_series);
  const auto n = static_cast<long>(x.size());
  const double scale = std::sqrt(sum_of_squares(x) * sum_of_squares(y));
  CrossCorrelation result;
  result.max_lag = max_lag;
  result.bound = 1.96 / std::sqrt(static_cast<double>(n));
  for (int lag = -max_lag; lag <= max_lag; ++lag) {
    double sum = 0.0;
    for (long t = std::max(0L, -static_cast<long>(lag)); t < n && t + lag < n; ++t)
      sum += x[static_cast<std::size_t>(t)] * y[static_cast<std::size_t>(t + lag)];
    const double value = scale > 0 ? sum / scale : 0.0;
    result.values.push_back(value);
    if (std::abs(value) > std::abs(result.peak)) {
      result.peak = value;
      result.peak_lag = lag;
    }
  }
  return result;
}

std::vector<double> band_power(std::span<const double> series, double dt,
                               std::span<const std::pair<double, double>> bands) {
  const std::vector<double> x = centred(series);
  std::vector<std::complex<double>> spectrum;
  Eigen::FFT<double> fft;
  fft.fwd(spectrum, x);
  const std::size_t n = x.size();
  const double resolution = 1.0 / (static_cast<double>(n) * dt);
  // One-sided periodogram: bins 1..n/2 (the mean is removed), doubled but for Nyquist.
  double total = 0.0;
  std::vector<double> power(bands.size(), 0.0);
  for (std::size_t k = 1; k <= n / 2; ++k) {
    const double weight = (2 * k == n) ? 1.0 : 2.0;
    const double p = weight * std::norm(spectrum[k]);
    total += p;
    const double frequency = static_cast<double>(k) * resolution;
    for (std::size_t b = 0; b < bands.size(); ++b) {
      if (frequency >= bands[b].first && frequency < bands[b].second) power[b] += p;
    }
  }
  for (double& share : power) share = total > 0 ? share / total : 0.0;
  return power;
}

Drift drift(std::span<const double> time, std::span<const double> series) {
  if (time.size() != series.size() || time.size() < 3)
    throw std::invalid_argument("drift: need as many times as values, at least three");
  const std::vector<double> t = centred(time);
  const std::vector<double> y = centred(series);
  const double stt = sum_of_squares(t);
  const double slope = std::inner_product(t.begin(), t.end(), y.begin(), 0.0) / stt;
  double residual = 0.0;
  for (std::size_t i = 0; i < y.size(); ++i) residual += std::pow(y[i] - slope * t[i], 2);
  const double error = std::sqrt(residual / static_cast<double>(y.size() - 2) / stt);
  return {slope, error, error > 0 ? slope / error : 0.0};
}

double correlation(std::span<const double> x_series, std::span<const double> y_series) {
  if (x_series.size() != y_series.size())
    throw std::invalid_argument("correlation: the series differ in length");
  const std::vector<double> x = centred(x_series);
  const std::vector<double> y = centred(y_series);
  const double scale = std::sqrt(sum_of_squares(x) * sum_of_squares(y));
  return scale > 0 ? std::inner_product(x.begin(), x.end(), y.begin(), 0.0) / scale : 0.0;
}

LoopSpectrum loop_spectrum(std::span<const double> deflection, std::span<const double> residual,
                           double dt, std::span<const std::pair<double, double>> bands) {
  if (deflection.size() != residual.size())
    throw std::invalid_argument("loop spectrum: the series differ in length");
  Eigen::FFT<double> fft;
  std::vector<std::complex<double>> x_spectrum, r_spectrum;
  fft.fwd(x_spectrum, centred(deflection));
  fft.fwd(r_spectrum, centred(residual));
  const std::size_t n = deflection.size();
  const double resolution = 1.0 / (static_cast<double>(n) * dt);
  std::vector<double> cross(bands.size(), 0.0), power(bands.size(), 0.0);
  double total = 0.0;
  for (std::size_t k = 1; k <= n / 2; ++k) {
    const double frequency = static_cast<double>(k) * resolution;
    total += std::norm(x_spectrum[k]);
    for (std::size_t b = 0; b < bands.size(); ++b) {
      if (frequency < bands[b].first || frequency >= bands[b].second) continue;
      cross[b] += (std::conj(x_spectrum[k]) * r_spectrum[k]).imag();
      power[b] += std::norm(x_spectrum[k]);
    }
  }
  LoopSpectrum result;
  std::vector<double> log_f, log_q;
  for (std::size_t b = 0; b < bands.size(); ++b) {
    // A band where x holds less than 1 % of its power says nothing of the loop.
    if (!(power[b] > 0.01 * total)) continue;
    const double centre = std::sqrt(bands[b].first * bands[b].second);
    result.frequency.push_back(centre);
    result.quadrature.push_back(cross[b] / power[b]);
    if (result.quadrature.back() != 0.0) {
      log_f.push_back(std::log(centre));
      log_q.push_back(std::log(std::abs(result.quadrature.back())));
    }
  }
  result.exponent = std::numeric_limits<double>::quiet_NaN();
  if (log_f.size() >= 2) {
    const std::vector<double> f = centred(log_f), q = centred(log_q);
    result.exponent = std::inner_product(f.begin(), f.end(), q.begin(), 0.0) / sum_of_squares(f);
  }
  return result;
}

}  // namespace tcpmsim::fit
