// The residual diagnostics of model discovery, against series whose structure is known: white
// noise, an AR(1) process, a delayed input, a sine, a ramp.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "identification/residual_diagnostics.h"
#include "sim/random_stream.h"

using namespace tcpmsim;
using namespace tcpmsim::fit;

namespace {

std::vector<double> white(std::size_t n, std::uint64_t seed) {
  RandomStream stream(seed, "white");
  std::vector<double> values(n);
  for (double& value : values) value = stream.normal();
  return values;
}

// x_t = phi x_{t-1} + e_t.
std::vector<double> autoregressive(double phi, std::size_t n, std::uint64_t seed) {
  std::vector<double> values = white(n, seed);
  for (std::size_t t = 1; t < n; ++t) values[t] += phi * values[t - 1];
  return values;
}

}  // namespace

TEST_CASE("Ljung-Box p-values of white noise are uniform: 5 % fall below 0.05") {
  const int trials = 400;
  int rejected = 0;
  for (int seed = 0; seed < trials; ++seed) {
    rejected += ljung_box(white(1000, static_cast<std::uint64_t>(seed)), 20).p_value < 0.05;
  }
  // Binomial(400, 0.05): mean 20, standard deviation 4.4.
  CHECK(std::abs(rejected - 20) <= 4 * 4.4);
}

TEST_CASE("Ljung-Box finds the memory of an AR(1) process, whose autocorrelation is phi^k") {
  const auto series = autoregressive(0.5, 5000, 3);
  CHECK(ljung_box(series, 20).p_value < 1e-10);
  const auto r = autocorrelation(series, 5);
  CHECK(r[0] == 1.0);
  for (int k = 1; k <= 5; ++k) {
    INFO("lag " << k);
    CHECK(std::abs(r[static_cast<std::size_t>(k)] - std::pow(0.5, k)) < 4.0 / std::sqrt(5000.0));
  }
}

TEST_CASE("Cross-correlation finds a residual that follows an input three samples late") {
  const std::size_t n = 4000;
  const auto input = white(n, 5);
  const auto noise = white(n, 6);
  std::vector<double> residual(n);
  for (std::size_t t = 0; t < n; ++t) residual[t] = (t >= 3 ? 0.5 * input[t - 3] : 0.0) + noise[t];
  const auto found = cross_correlation(input, residual, 10);
  CHECK(found.peak_lag == 3);
  // c = 0.5 / sqrt(1 + 0.25) for unit variances.
  CHECK(found.peak == Approx(0.5 / std::sqrt(1.25)).margin(4.0 / std::sqrt(double(n))));
  const auto independent = cross_correlation(input, noise, 10);
  CHECK(std::abs(independent.peak) < 4.0 / std::sqrt(double(n)));
  CHECK(independent.bound == Approx(1.96 / std::sqrt(double(n))));
}

TEST_CASE("Band power puts a sine's variance in its band") {
  const std::size_t n = 6400;  // 400 s at 16 Hz
  const double dt = 1.0 / 16.0;
  const auto noise = white(n, 8);
  std::vector<double> series(n);
  for (std::size_t t = 0; t < n; ++t)
    series[t] = std::sin(2 * std::numbers::pi * 0.1 * double(t) * dt) + 0.05 * noise[t];
  const std::vector<std::pair<double, double>> bands = {{0.0, 0.05}, {0.05, 0.2}, {0.2, 8.1}};
  const auto shares = band_power(series, dt, bands);
  // Sine variance 1/2; noise 0.0025 spread evenly over 0-8 Hz.
  const double noise_share = 0.0025 / (0.5 + 0.0025);
  CHECK(shares[1] == Approx(0.5 / 0.5025 + noise_share * 0.15 / 8.0).margin(0.002));
  CHECK(shares[0] + shares[1] + shares[2] == Approx(1.0).margin(1e-12));
}

TEST_CASE("Drift is the slope of a ramp, within its standard error; noise alone has none") {
  const std::size_t n = 2000;
  const auto noise = white(n, 9);
  std::vector<double> time(n), ramp(n);
  for (std::size_t t = 0; t < n; ++t) {
    time[t] = 0.1 * double(t);
    ramp[t] = 0.003 * time[t] + noise[t];
  }
  const Drift found = drift(time, ramp);
  CHECK(std::abs(found.slope - 0.003) < 3 * found.standard_error);
  // sigma / sqrt(sum (t - mean)^2) for unit noise.
  const double expected_error =
      1.0 / std::sqrt(0.01 * double(n) * (double(n) * double(n) - 1) / 12.0);
  CHECK(found.standard_error == Approx(expected_error).epsilon(0.05));
  CHECK(found.t_statistic > 4);  // expected 0.003 / 3.9e-4 = 7.8, +-1
  CHECK(std::abs(drift(time, noise).t_statistic) < 4);
}

TEST_CASE("The loop a viscous residual draws grows as f, with quadrature 2 pi f c") {
  // x: three sines in separate bands; r = c dx/dt, a dashpot's force: pi q a^2 per cycle.
  const double dt = 1.0 / 16.0, c = 0.3;
  const std::size_t n = 16 * 1000;
  const std::vector<double> frequencies = {0.02, 0.08, 0.32};
  std::vector<double> x(n, 0.0), r(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) * dt;
    for (double f : frequencies) {
      x[i] += 1e-3 * std::sin(2 * std::numbers::pi * f * t);
      r[i] += c * 1e-3 * 2 * std::numbers::pi * f * std::cos(2 * std::numbers::pi * f * t);
    }
  }
  const std::vector<std::pair<double, double>> bands = {{0.01, 0.04}, {0.04, 0.16}, {0.16, 0.64}};
  const LoopSpectrum loop = loop_spectrum(x, r, dt, bands);
  REQUIRE(loop.quadrature.size() == 3);
  for (std::size_t b = 0; b < 3; ++b)
    CHECK(loop.quadrature[b] == Approx(2 * std::numbers::pi * frequencies[b] * c).epsilon(1e-6));
  CHECK(loop.exponent == Approx(1.0).epsilon(1e-6));
  // An elastic residual (in phase with x) draws no loop.
  const LoopSpectrum elastic = loop_spectrum(x, x, dt, bands);
  for (double q : elastic.quadrature) CHECK(std::abs(q) < 1e-12);
}

TEST_CASE("The loop of a rate-independent relay, F sign(dx/dt), does not depend on frequency") {
  // Its first harmonic in quadrature with x = a sin(wt) is (4 F / pi) cos(wt): q = 4 F / (pi a)
  // at any frequency (describing function of an ideal relay).
  const double dt = 1.0 / 16.0, a = 2e-3, force = 5e-3;
  const std::size_t n = 16 * 1000;
  std::vector<double> quadratures;
  for (double f : {0.02, 0.08}) {
    std::vector<double> x(n), r(n);
    for (std::size_t i = 0; i < n; ++i) {
      const double phase = 2 * std::numbers::pi * f * static_cast<double>(i) * dt;
      x[i] = a * std::sin(phase);
      r[i] = std::cos(phase) > 0 ? force : -force;
    }
    const std::vector<std::pair<double, double>> band = {{0.5 * f, 2 * f}};
    const LoopSpectrum loop = loop_spectrum(x, r, dt, band);
    REQUIRE(loop.quadrature.size() == 1);
    quadratures.push_back(loop.quadrature[0]);
    CHECK(loop.quadrature[0] == Approx(4 * force / (std::numbers::pi * a)).epsilon(0.01));
  }
  CHECK(quadratures[0] == Approx(quadratures[1]).epsilon(0.01));
}

TEST_CASE("Correlation is Pearson's: 1 for a line, -1 reversed, near 0 for independent noise") {
  const auto x = white(2000, 11);
  std::vector<double> line, reversed;
  for (double v : x) {
    line.push_back(3 * v + 2);
    reversed.push_back(-v);
  }
  CHECK(correlation(x, line) == Approx(1.0).epsilon(1e-12));
  CHECK(correlation(x, reversed) == Approx(-1.0).epsilon(1e-12));
  CHECK(std::abs(correlation(x, white(2000, 12))) < 4 / std::sqrt(2000.0));
}
