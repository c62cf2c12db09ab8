#include "analysis/frequency_response.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <stdexcept>
#include <string>
#include <unsupported/Eigen/FFT>

#include "analysis/series_checks.h"
#include "sim/not_a_number.h"

namespace tcpmsim {

SineFit fit_sine(std::span<const double> time, std::span<const double> values, double frequency,
                 double origin, double begin, double end) {
  const char* what = "fit_sine";
  require_same_length(time.size(), values.size(), what);
  if (!(frequency > 0.0)) throw std::invalid_argument("fit_sine: frequency must be positive");
  const auto first = std::lower_bound(time.begin(), time.end(), begin) - time.begin();
  const auto last = std::lower_bound(time.begin(), time.end(), end) - time.begin();
  const auto count = last - first;
  if (count < 3) throw std::invalid_argument("fit_sine: fewer than three samples in the window");
  const auto window_time =
      time.subspan(static_cast<std::size_t>(first), static_cast<std::size_t>(count));
  const auto window_values =
      values.subspan(static_cast<std::size_t>(first), static_cast<std::size_t>(count));
  require_finite(window_time, what, "time");
  require_finite(window_values, what, "values");

  const double omega = 2.0 * std::numbers::pi * frequency;
  Eigen::MatrixXd design(count, 3);
  Eigen::VectorXd observed(count);
  for (Eigen::Index i = 0; i < count; ++i) {
    const double angle = omega * (window_time[static_cast<std::size_t>(i)] - origin);
    design(i, 0) = std::sin(angle);
    design(i, 1) = std::cos(angle);
    design(i, 2) = 1.0;
    observed(i) = window_values[static_cast<std::size_t>(i)];
  }
  const Eigen::Vector3d solution = design.colPivHouseholderQr().solve(observed);
  SineFit fit;
  fit.frequency = frequency;
  // a sin + b cos = A sin(angle + phase) with A cos(phase) = a, A sin(phase) = b.
  fit.amplitude = std::hypot(solution(0), solution(1));
  fit.phase = wrap_phase(std::atan2(solution(1), solution(0)));
  fit.offset = solution(2);
  fit.rms_residual = std::sqrt((design * solution - observed).squaredNorm() / double(count));
  fit.samples = static_cast<std::size_t>(count);
  return fit;
}

std::vector<FrequencyResponsePoint> sweep_frequency_response(std::span<const double> time,
                                                             std::span<const double> reference,
                                                             std::span<const double> response,
                                                             const SweepSchedule& schedule,
                                                             double fit_periods) {
  const char* what = "sweep_frequency_response";
  require_same_length(time.size(), reference.size(), what);
  require_same_length(time.size(), response.size(), what);
  require_time(time, what);
  if (!(fit_periods > 0.0 && fit_periods <= schedule.periods))
    throw std::invalid_argument("sweep_frequency_response: need 0 < fit periods <= periods");
  std::vector<FrequencyResponsePoint> points;
  for (std::size_t i = 0; i < schedule.frequencies.size(); ++i) {
    const double f = schedule.frequencies[i];
    const double end = schedule.end_time(i);
    const double begin = end - fit_periods / f;
    FrequencyResponsePoint point;
    point.frequency = f;
    point.reference = fit_sine(time, reference, f, schedule.start_times[i], begin, end);
    point.response = fit_sine(time, response, f, schedule.start_times[i], begin, end);
    if (!(point.reference.amplitude > 0.0))
      throw std::invalid_argument("sweep_frequency_response: the reference does not oscillate");
    point.magnitude = point.response.amplitude / point.reference.amplitude;
    point.magnitude_db = 20.0 * std::log10(point.magnitude);
    const double phase = wrap_phase(point.response.phase - point.reference.phase);
    if (points.empty()) {
      point.phase = phase;
    } else {
      // The representative of `phase` modulo 2 pi nearest to the previous point's phase.
      const double previous = points.back().phase;
      point.phase = previous + wrap_phase(phase - previous);
    }
    points.push_back(point);
  }
  return points;
}

std::optional<double> bandwidth_3db(std::span<const FrequencyResponsePoint> points) {
  const double level = 20.0 * std::log10(1.0 / std::numbers::sqrt2);  // -3.0103 dB
  for (std::size_t i = 1; i < points.size(); ++i) {
    if (!(points[i].frequency > points[i - 1].frequency))
      throw std::invalid_argument("bandwidth_3db: frequencies must increase");
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (points[i].magnitude_db > level) continue;
    if (i == 0) return std::nullopt;  // below -3 dB from the first frequency on
    const double x0 = std::log10(points[i - 1].frequency), x1 = std::log10(points[i].frequency);
    const double d0 = points[i - 1].magnitude_db, d1 = points[i].magnitude_db;
    return std::pow(10.0, x0 + (level - d0) / (d1 - d0) * (x1 - x0));
  }
  return std::nullopt;
}

}  // namespace tcpmsim

namespace tcpmsim {

namespace {
// The 95 % circle of a complex Gaussian with independent components of standard deviation s
// has radius sqrt(chi2_2(0.95)) s = sqrt(-2 ln 0.05) s.
const double kCircle95 = std::sqrt(-2.0 * std::log(0.05));

// A frequency the record excites, and the inputs that excite it.
struct ExcitedLine {
  double frequency = 0.0;
  std::vector<std::size_t> inputs;
};

// Lines closer than this fraction of the resolution 1 / (window length) are one line: their sines
// differ by less than a twentieth of a period over the window, too little to fit apart.
constexpr double kCoincident = 0.05;

// Every input's lines, those closer than `resolution` merged into one.
std::vector<ExcitedLine> merged_lines(std::span<const ExcitedInput> inputs, double resolution) {
  std::vector<std::pair<double, std::size_t>> all;
  for (std::size_t j = 0; j < inputs.size(); ++j)
    for (const double f : inputs[j].lines) all.emplace_back(f, j);
  std::sort(all.begin(), all.end());
  std::vector<ExcitedLine> lines;
  for (const auto& [frequency, input] : all) {
    if (!lines.empty() && frequency - lines.back().frequency < resolution) {
      auto& owners = lines.back().inputs;
      if (std::find(owners.begin(), owners.end(), input) == owners.end()) owners.push_back(input);
      continue;
    }
    lines.push_back({frequency, {input}});
  }
  return lines;
}

// The names of the inputs of `line` other than `input`.
std::string other_inputs(const ExcitedLine& line, std::size_t input,
                         std::span<const ExcitedInput> inputs) {
  std::string names;
  for (const std::size_t other : line.inputs) {
    if (other == input) continue;
    names += (names.empty() ? "" : ", ") + inputs[other].name;
  }
  return names;
}

// Magnitude, dB and the phase unwrapped along the list (each within pi of the previous).
void complete(std::vector<ResponseEstimate>& estimates) {
  double previous = kNaN;
  for (auto& estimate : estimates) {
    if (!std::isfinite(estimate.response.real())) {
      estimate.magnitude = estimate.magnitude_db = estimate.phase = kNaN;
      continue;
    }
    estimate.magnitude = std::abs(estimate.response);
    estimate.magnitude_db = 20.0 * std::log10(estimate.magnitude);
    const double phase = std::arg(estimate.response);
    estimate.phase = std::isfinite(previous) ? previous + wrap_phase(phase - previous) : phase;
    previous = estimate.phase;
  }
}

// Phasors P = a + i b of y ~ c + sum a sin(w t) + b cos(w t) at every line, and the variance
// of each component of P.
struct LineFit {
  std::vector<std::complex<double>> phasors;
  std::vector<double> component_variances;
};

LineFit fit_lines(const Eigen::ColPivHouseholderQR<Eigen::MatrixXd>& qr,
                  const Eigen::MatrixXd& covariance, const Eigen::MatrixXd& design,
                  std::span<const double> series) {
  const auto rows = static_cast<Eigen::Index>(series.size());
  const Eigen::VectorXd y = Eigen::Map<const Eigen::VectorXd>(series.data(), rows);
  const Eigen::VectorXd beta = qr.solve(y);
  const double freedom = double(rows - design.cols());
  const double variance = (y - design * beta).squaredNorm() / freedom;
  LineFit fit;
  for (Eigen::Index l = 0; 2 * l + 2 < design.cols(); ++l) {
    const Eigen::Index a = 1 + 2 * l, b = 2 + 2 * l;
    fit.phasors.emplace_back(beta(a), beta(b));
    fit.component_variances.push_back(variance * 0.5 * (covariance(a, a) + covariance(b, b)));
  }
  return fit;
}

void require_inputs(std::span<const double> time, std::span<const ExcitedInput> inputs,
                    std::span<const double> output, const char* what) {
  if (inputs.empty()) throw std::invalid_argument(std::string(what) + ": no input");
  require_time(time, what);
  require_same_length(time.size(), output.size(), what);
  require_finite(output, what, "output");
  for (const auto& input : inputs) {
    require_same_length(time.size(), input.values.size(), what);
    require_finite(input.values, what, input.name.c_str());
  }
}
}  // namespace

std::vector<std::vector<ResponseEstimate>> line_response(std::span<const double> time,
                                                         std::span<const ExcitedInput> inputs,
                                                         std::span<const double> output) {
  const char* what = "line_response";
  require_inputs(time, inputs, output, what);
  const double length = time.back() - time.front();
  const auto lines = merged_lines(inputs, kCoincident / length);
  const auto rows = static_cast<Eigen::Index>(time.size());
  const auto columns = static_cast<Eigen::Index>(1 + 2 * lines.size());
  if (lines.empty()) throw std::invalid_argument("line_response: no excited line");
  if (rows <= columns)
    throw std::invalid_argument("line_response: " + std::to_string(time.size()) +
                                " samples cannot separate " + std::to_string(lines.size()) +
                                " lines");
  Eigen::MatrixXd design(rows, columns);
  for (Eigen::Index i = 0; i < rows; ++i) {
    const double t = time[static_cast<std::size_t>(i)] - time.front();
    design(i, 0) = 1.0;
    for (std::size_t l = 0; l < lines.size(); ++l) {
      const double angle = 2.0 * std::numbers::pi * lines[l].frequency * t;
      design(i, static_cast<Eigen::Index>(1 + 2 * l)) = std::sin(angle);
      design(i, static_cast<Eigen::Index>(2 + 2 * l)) = std::cos(angle);
    }
  }
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(design);
  if (qr.rank() < columns)
    throw std::invalid_argument("line_response: the lines cannot be told apart in the window");
  const Eigen::MatrixXd covariance = (design.transpose() * design).inverse();
  const LineFit y = fit_lines(qr, covariance, design, output);

  std::vector<std::vector<ResponseEstimate>> estimates(inputs.size());
  for (std::size_t j = 0; j < inputs.size(); ++j) {
    const LineFit u = fit_lines(qr, covariance, design, inputs[j].values);
    for (std::size_t l = 0; l < lines.size(); ++l) {
      const auto& owners = lines[l].inputs;
      if (std::find(owners.begin(), owners.end(), j) == owners.end()) continue;
      ResponseEstimate estimate;
      estimate.frequency = lines[l].frequency;
      estimate.overlap = other_inputs(lines[l], j, inputs);
      if (!estimate.overlap.empty()) {
        estimate.response = {kNaN, kNaN};
        estimate.radius_95 = estimate.coherence = kNaN;
      } else {
        const std::complex<double> Y = y.phasors[l], U = u.phasors[l];
        estimate.response = Y / U;
        const double relative =
            y.component_variances[l] / std::norm(Y) + u.component_variances[l] / std::norm(U);
        estimate.radius_95 = kCircle95 * std::abs(estimate.response) * std::sqrt(relative);
        estimate.coherence = std::norm(Y) / (std::norm(Y) + 2.0 * y.component_variances[l]);
      }
      estimates[j].push_back(estimate);
    }
    complete(estimates[j]);
  }
  return estimates;
}

namespace {

// One segment's contribution to the spectra at every bin: u u^H, Y u^H and |Y|^2.
struct SegmentSpectra {
  std::vector<Eigen::MatrixXcd> suu;
  std::vector<Eigen::RowVectorXcd> syu;
  std::vector<double> syy;
};

// The first differences of `series` from `first` over `length` + 1 samples, less their mean,
// times the Hann window, transformed.
std::vector<std::complex<double>> segment_spectrum(Eigen::FFT<double>& fft,
                                                   std::span<const double> series,
                                                   std::size_t first,
                                                   const std::vector<double>& window) {
  const std::size_t length = window.size();
  std::vector<double> segment(length);
  for (std::size_t i = 0; i < length; ++i) segment[i] = series[first + i + 1] - series[first + i];
  const double mean = std::accumulate(segment.begin(), segment.end(), 0.0) / double(length);
  for (std::size_t i = 0; i < length; ++i) segment[i] = (segment[i] - mean) * window[i];
  std::vector<std::complex<double>> transformed;
  fft.fwd(transformed, segment);
  return transformed;
}

SegmentSpectra segment_spectra(Eigen::FFT<double>& fft, std::span<const ExcitedInput> inputs,
                               std::span<const double> output, std::size_t first,
                               const std::vector<double>& window) {
  const std::size_t bins = window.size() / 2, q = inputs.size();
  const auto Y = segment_spectrum(fft, output, first, window);
  std::vector<std::vector<std::complex<double>>> U;
  for (const auto& input : inputs) U.push_back(segment_spectrum(fft, input.values, first, window));
  SegmentSpectra spectra;
  for (std::size_t k = 0; k < bins; ++k) {
    Eigen::VectorXcd u(static_cast<Eigen::Index>(q));
    for (std::size_t j = 0; j < q; ++j) u(static_cast<Eigen::Index>(j)) = U[j][k + 1];
    spectra.suu.push_back(u * u.adjoint());
    spectra.syu.push_back(Y[k + 1] * u.adjoint());
    spectra.syy.push_back(std::norm(Y[k + 1]));
  }
  return spectra;
}

}  // namespace

std::vector<std::vector<ResponseEstimate>> spectral_response(std::span<const double> time,
                                                             std::span<const ExcitedInput> inputs,
                                                             std::span<const double> output,
                                                             std::size_t segment_samples) {
  const char* what = "spectral_response";
  require_inputs(time, inputs, output, what);
  const std::size_t n = time.size() - 1, q = inputs.size(), length = segment_samples;  // n steps
  if (length < 8 || length > n)
    throw std::invalid_argument("spectral_response: a segment of " + std::to_string(length) +
                                " samples does not fit " + std::to_string(n + 1) + " samples");
  const double interval = (time.back() - time.front()) / double(n);
  for (std::size_t i = 1; i <= n; ++i)
    if (std::abs(time[i] - time[i - 1] - interval) > 1e-6 * interval)
      throw std::invalid_argument("spectral_response: the samples are not evenly spaced");
  const std::size_t hop = length / 2, segments = 1 + (n - length) / hop;
  if (segments < q + 2)
    throw std::invalid_argument("spectral_response: " + std::to_string(segments) +
                                " segments cannot separate " + std::to_string(q) +
                                " inputs and bound the error; shorten the segments");
  std::vector<double> window(length);
  for (std::size_t i = 0; i < length; ++i)
    window[i] = 0.5 - 0.5 * std::cos(2.0 * std::numbers::pi * double(i) / double(length));
  Eigen::FFT<double> fft;
  std::vector<SegmentSpectra> parts;
  for (std::size_t s = 0; s < segments; ++s)
    parts.push_back(segment_spectra(fft, inputs, output, s * hop, window));

  const std::size_t bins = length / 2;
  std::vector<double> peak(q, 0.0);
  std::vector<std::vector<ResponseEstimate>> estimates(q);
  std::vector<std::vector<std::complex<double>>> per_bin(bins);
  for (std::size_t k = 0; k < bins; ++k) {
    Eigen::MatrixXcd suu = Eigen::MatrixXcd::Zero(Eigen::Index(q), Eigen::Index(q));
    Eigen::RowVectorXcd syu = Eigen::RowVectorXcd::Zero(Eigen::Index(q));
    double syy = 0.0;
    for (const auto& part : parts) suu += part.suu[k], syu += part.syu[k], syy += part.syy[k];
    for (std::size_t j = 0; j < q; ++j)
      peak[j] = std::max(peak[j], suu(Eigen::Index(j), Eigen::Index(j)).real());
    const Eigen::RowVectorXcd H = syu * suu.inverse();
    // The jackknife: H without each segment in turn; the spread of those estimates is the
    // estimate's variance (Thomson and Chave 1991), whatever the data's distribution.
    Eigen::RowVectorXcd mean = Eigen::RowVectorXcd::Zero(Eigen::Index(q));
    std::vector<Eigen::RowVectorXcd> deleted;
    for (const auto& part : parts) {
      deleted.push_back((syu - part.syu[k]) * (suu - part.suu[k]).inverse());
      mean += deleted.back() / double(segments);
    }
    Eigen::RowVectorXd variance = Eigen::RowVectorXd::Zero(Eigen::Index(q));
    for (const auto& estimate : deleted)
      variance += (estimate - mean).cwiseAbs2() * (double(segments - 1) / double(segments));
    const double coherence = std::clamp((H * syu.adjoint())(0).real() / syy, 0.0, 1.0);
    for (std::size_t j = 0; j < q; ++j) {
      ResponseEstimate estimate;
      estimate.frequency = double(k + 1) / (double(length) * interval);
      estimate.response = H(Eigen::Index(j));
      estimate.coherence = coherence;
      estimate.radius_95 = kCircle95 * std::sqrt(0.5 * variance(Eigen::Index(j)));
      estimates[j].push_back(estimate);
    }
    for (std::size_t j = 0; j < q; ++j) per_bin[k].push_back(suu(Eigen::Index(j), Eigen::Index(j)));
  }
  // Only the frequencies where the estimate says something: the input excites them (its
  // differenced auto-spectrum above 1 % of its peak) and H stands out of its own confidence
  // region (|H| >= 2 radius); from the second bin on.
  for (std::size_t j = 0; j < q; ++j) {
    std::vector<ResponseEstimate> kept;
    for (std::size_t k = 1; k < bins; ++k) {  // bin 1 lies in the window's main lobe about DC
      const ResponseEstimate& estimate = estimates[j][k];
      if (per_bin[k][j].real() >= 0.01 * peak[j] &&
          std::abs(estimate.response) >= 2.0 * estimate.radius_95)
        kept.push_back(estimate);
    }
    estimates[j] = std::move(kept);
    complete(estimates[j]);
  }
  return estimates;
}

std::optional<double> estimate_bandwidth_3db(std::span<const ResponseEstimate> estimates,
                                             double reference_magnitude) {
  std::vector<FrequencyResponsePoint> points;
  for (const auto& estimate : estimates) {
    if (!std::isfinite(estimate.magnitude)) continue;
    FrequencyResponsePoint point;
    point.frequency = estimate.frequency;
    point.magnitude = estimate.magnitude / reference_magnitude;
    point.magnitude_db = 20.0 * std::log10(point.magnitude);
    points.push_back(point);
  }
  return bandwidth_3db(points);
}

}  // namespace tcpmsim
