#include "analysis/describing_function.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <unsupported/Eigen/MatrixFunctions>

#include "models/laws/sls.h"
#include "models/laws/thermal_force.h"

namespace tcpmsim {

namespace {
using Complex = std::complex<double>;
using Response = std::function<Complex(double)>;
constexpr double kPi = std::numbers::pi;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

double clamp_to(double value, double lower, double upper) {
  return std::max(lower, std::min(upper, value));
}

// Points of a grid geometric in omega: dense near DC, where the loop's slow poles act.
constexpr int kGridPoints = 4000;

// Every omega in (w_min, w_max) at which Im G changes sign, refined by bisection, with G there.
std::vector<LoopCrossing> real_axis_crossings(const Response& loop, double w_min, double w_max,
                                              double to_hertz) {
  std::vector<LoopCrossing> crossings;
  const double ratio = std::log(w_max / w_min);
  double w_previous = w_min;
  double im_previous = loop(w_min).imag();
  for (int i = 1; i <= kGridPoints; ++i) {
    const double w = w_min * std::exp(ratio * i / kGridPoints);
    const double im = loop(w).imag();
    if (im == 0.0 || (im_previous != 0.0 && (im > 0.0) != (im_previous > 0.0))) {
      double low = w_previous, high = w;
      double im_low = im_previous;
      if (im != 0.0) {
        for (int iteration = 0; iteration < 200 && high - low > 4e-16 * high; ++iteration) {
          const double middle = 0.5 * (low + high);
          const double im_middle = loop(middle).imag();
          if ((im_middle > 0.0) == (im_low > 0.0) && im_middle != 0.0) {
            low = middle;
            im_low = im_middle;
          } else {
            high = middle;
          }
        }
      }
      const double at = im == 0.0 ? w : 0.5 * (low + high);
      crossings.push_back({at * to_hertz, loop(at).real(), false});
    }
    w_previous = w;
    im_previous = im;
  }
  return crossings;
}

// The demand's mean b for which the integral balances at amplitude A:
// b - P* = G(1) (mean P(b, A) - P*), monotone in b for G(1) < 1.
template <typename Saturation>
double balanced_bias(const Saturation& saturation, double amplitude, double dc_gain,
                     double operating_power, const PowerLimits& limits) {
  const double reach = (std::abs(dc_gain) + 1.0) * (limits.max - limits.min);
  double low = operating_power - reach, high = operating_power + reach;
  auto imbalance = [&](double bias) {
    return bias - operating_power -
           dc_gain * (saturation(bias, amplitude, limits.min, limits.max).mean - operating_power);
  };
  for (int iteration = 0; iteration < 300; ++iteration) {
    const double middle = 0.5 * (low + high);
    if (middle <= low || middle >= high) break;
    (imbalance(middle) > 0.0 ? high : low) = middle;
  }
  return 0.5 * (low + high);
}

template <typename Saturation>
LimitCycle harmonic_balance(const Saturation& saturation, const LoopCrossing& crossing,
                            double dc_gain, double operating_power, const PowerLimits& limits) {
  const double wanted = 1.0 / crossing.value;  // N(A) = 1 / G
  auto shortfall = [&](double amplitude) {
    const double bias = balanced_bias(saturation, amplitude, dc_gain, operating_power, limits);
    return saturation(bias, amplitude, limits.min, limits.max).gain - wanted;
  };
  const double span = limits.max - limits.min;
  double low = 1e-12 * span, high = span;
  for (int doubling = 0; doubling < 200 && shortfall(high) > 0.0; ++doubling) high *= 2.0;
  for (int iteration = 0; iteration < 200; ++iteration) {
    const double middle = std::sqrt(low * high);
    if (middle <= low || middle >= high) break;
    (shortfall(middle) > 0.0 ? low : high) = middle;
  }
  LimitCycle cycle;
  cycle.frequency = crossing.frequency;
  cycle.loop_gain = crossing.value;
  cycle.demand_amplitude = std::sqrt(low * high);
  cycle.demand_mean =
      balanced_bias(saturation, cycle.demand_amplitude, dc_gain, operating_power, limits);
  cycle.power_mean =
      saturation(cycle.demand_mean, cycle.demand_amplitude, limits.min, limits.max).mean;
  cycle.power_low = clamp_to(cycle.demand_mean - cycle.demand_amplitude, limits.min, limits.max);
  cycle.power_high = clamp_to(cycle.demand_mean + cycle.demand_amplitude, limits.min, limits.max);
  return cycle;
}

// Whether a period-2 orbit of the sampled loop attracts. Perturbations pass the saturation with
// its slope s[k] at the orbit, 1 where the demand is inside the limits and 0 where it is
// clipped. Both clipped: nothing propagates, the orbit is super-stable. One clipped: s[k] =
// (1 + (-1)^k)/2 couples a perturbation at w with one at w + pi/T, and
// dP_d(w) = G(w) (dP_d(w) + dP_d(w + pi/T)) / 2 has solutions where G_e = (G(z) + G(-z))/2 = 1.
// G_e is a function of z^2 with G's poles (inside the unit circle), so the orbit attracts iff
// 1 - G_e winds zero times around 0 as z^2 goes once round the circle (w in [0, pi/T)).
bool period_two_orbit_attracts(const Response& loop, double period, const LimitCycle& cycle,
                               const PowerLimits& limits) {
  auto inside = [&](double demand) { return demand > limits.min && demand < limits.max; };
  const bool high_passes = inside(cycle.demand_mean + cycle.demand_amplitude);
  const bool low_passes = inside(cycle.demand_mean - cycle.demand_amplitude);
  if (!high_passes && !low_passes) return true;
  if (high_passes && low_passes) return false;  // not a saturated orbit (cannot balance)
  const double nyquist = kPi / period;
  constexpr int kPoints = 40000;
  double winding = 0.0;
  Complex previous = 1.0 - 0.5 * (loop(0.0) + loop(nyquist));
  for (int i = 1; i <= kPoints; ++i) {
    const double omega = nyquist * i / kPoints;
    const Complex value = 1.0 - 0.5 * (loop(omega) + loop(omega + nyquist));
    winding += std::arg(value / previous);
    previous = value;
  }
  return std::abs(winding) < kPi;  // zero turns (a turn is 2 pi)
}

// Verdict and harmonic balance from the crossings.
LimitCyclePrediction conclude(std::vector<LoopCrossing> crossings, double dc_gain,
                              const PowerLimits& limits, double operating_power,
                              const Response& loop, double period, const Response* measurement) {
  if (!(limits.min < limits.max)) throw std::invalid_argument("power limits: need min < max");
  LimitCyclePrediction prediction;
  prediction.operating_power = operating_power;
  prediction.dc_gain = dc_gain;
  prediction.crossings = std::move(crossings);
  double largest = dc_gain;
  for (const auto& crossing : prediction.crossings) largest = std::max(largest, crossing.value);
  prediction.crossing_margin = largest > 0.0 ? 1.0 / largest : kInfinity;

  if (!(operating_power > limits.min && operating_power < limits.max)) {
    prediction.verdict = LoopVerdict::saturated;
    return prediction;
  }
  if (dc_gain >= 1.0) {
    prediction.verdict = LoopVerdict::latch_up;
    return prediction;
  }
  for (const auto& crossing : prediction.crossings) {
    if (!(crossing.value > 1.0)) continue;
    LimitCycle cycle =
        crossing.at_nyquist
            ? harmonic_balance(&saturate_alternation, crossing, dc_gain, operating_power, limits)
            : harmonic_balance(&saturate_sinusoid, crossing, dc_gain, operating_power, limits);
    cycle.at_nyquist = crossing.at_nyquist;
    const double omega = 2.0 * kPi * crossing.frequency;
    if (!cycle.at_nyquist)
      cycle.third_harmonic_ratio = std::abs(loop(3.0 * omega)) / crossing.value;
    cycle.power_fundamental = cycle.demand_amplitude / crossing.value;  // N(A) A = A / G
    if (measurement)
      cycle.estimate_amplitude = std::abs((*measurement)(omega)) * cycle.power_fundamental;
    prediction.cycles.push_back(cycle);
  }
  std::sort(prediction.cycles.begin(), prediction.cycles.end(),
            [](const LimitCycle& a, const LimitCycle& b) { return a.loop_gain > b.loop_gain; });
  if (!prediction.cycles.empty()) {
    // With G stable, 1/N(A) leaves the encircled part of the real axis at the largest crossing:
    // beyond it the oscillation decays, inside it grows. That solution attracts, if (at
    // Nyquist) its orbit does.
    LimitCycle& largest_cycle = prediction.cycles.front();
    largest_cycle.stable =
        !largest_cycle.at_nyquist || period_two_orbit_attracts(loop, period, largest_cycle, limits);
    prediction.verdict = LoopVerdict::limit_cycle;
  }
  return prediction;
}

// Crossings of a sampled loop over (0, pi/T], the Nyquist point included when G is real there.
std::vector<LoopCrossing> sampled_crossings(const Response& loop, double period) {
  const double nyquist = kPi / period;
  const double to_hertz = 1.0 / (2.0 * kPi);
  auto crossings = real_axis_crossings(loop, 1e-6 * nyquist, nyquist * (1.0 - 1e-9), to_hertz);
  // Real there for any real-coefficient loop; not quite with a fractional median delay.
  const Complex at_nyquist = loop(nyquist);
  if (std::abs(at_nyquist.imag()) <= 1e-9 * std::abs(at_nyquist))
    crossings.push_back({nyquist * to_hertz, at_nyquist.real(), true});
  return crossings;
}

bool oscillates(const SampledLoop& loop) {
  if (loop.dc_gain() >= 1.0) return true;
  for (const auto& crossing : sampled_crossings(loop, loop.period())) {
    if (crossing.value >= 1.0) return true;
  }
  return false;
}
}  // namespace

double saturation_describing_function(double amplitude, double limit) {
  if (!(limit > 0.0)) throw std::invalid_argument("saturation: the limit must be positive");
  if (amplitude <= limit) return 1.0;
  const double ratio = limit / amplitude;
  return 2.0 / kPi * (std::asin(ratio) + ratio * std::sqrt(1.0 - ratio * ratio));
}

SaturatedOscillation saturate_sinusoid(double bias, double amplitude, double lower, double upper) {
  if (!(lower < upper)) throw std::invalid_argument("saturation: need lower < upper");
  if (!(amplitude > 0.0)) {
    // The small-signal limit: the slope at the bias.
    return {clamp_to(bias, lower, upper), bias > lower && bias < upper ? 1.0 : 0.0};
  }
  // y(theta) = clamp(b + A sin theta). With s = sin theta, the input leaves [lower, upper]
  // for s outside [s_l, s_u]; integrate y and y sin theta over a period in s (dtheta =
  // ds / sqrt(1 - s^2), twice over [-1, 1]).
  const double s_l = clamp_to((lower - bias) / amplitude, -1.0, 1.0);
  const double s_u = clamp_to((upper - bias) / amplitude, -1.0, 1.0);
  const double c_l = std::sqrt(1.0 - s_l * s_l), c_u = std::sqrt(1.0 - s_u * s_u);
  const double a_l = std::asin(s_l), a_u = std::asin(s_u);
  const double mean = (lower * (a_l + 0.5 * kPi) + bias * (a_u - a_l) + amplitude * (c_l - c_u) +
                       upper * (0.5 * kPi - a_u)) /
                      kPi;
  const double fundamental = 2.0 / kPi *
                             (-lower * c_l + upper * c_u + bias * (c_l - c_u) +
                              0.5 * amplitude * (a_u - s_u * c_u - a_l + s_l * c_l));
  return {mean, fundamental / amplitude};
}

SaturatedOscillation saturate_alternation(double bias, double amplitude, double lower,
                                          double upper) {
  if (!(lower < upper)) throw std::invalid_argument("saturation: need lower < upper");
  if (!(amplitude > 0.0)) {
    return {clamp_to(bias, lower, upper), bias > lower && bias < upper ? 1.0 : 0.0};
  }
  const double high = clamp_to(bias + amplitude, lower, upper);
  const double low = clamp_to(bias - amplitude, lower, upper);
  return {0.5 * (high + low), (high - low) / (2.0 * amplitude)};
}

std::complex<double> RationalFunction::operator()(std::complex<double> s) const {
  auto horner = [s](const std::vector<double>& coefficients) {
    Complex value = 0.0;
    for (const double c : coefficients) value = value * s + c;
    return value;
  };
  return horner(numerator) / horner(denominator);
}

RationalFunction force_loop_transfer_function(const PidGains& gains, double heating_gain,
                                              double cooling_rate) {
  if (!std::isfinite(gains.integral_time) || !(gains.integral_time > 0.0))
    throw std::invalid_argument("(7.10) needs a finite, positive integral time");
  const double kp = gains.proportional, ti = gains.integral_time, td = gains.derivative_time;
  const double kP = heating_gain, kc = cooling_rate;
  // (7.10), re-derived in the header.
  return {{-kp * td * kP, 1.0 / ti - kP * kp, (kc - kP * kp) / ti}, {1.0, 1.0 / ti + kc, kc / ti}};
}

SampledLoop::SampledLoop(PidGains gains, double period, Response measurement)
    : gains_(gains), period_(period), measurement_(std::move(measurement)) {
  if (!(period_ > 0.0)) throw std::invalid_argument("sampled loop: period must be positive");
  if (gains_.proportional == 0.0) throw std::invalid_argument("sampled loop: K_p must be non-zero");
  if (!(gains_.integral_time > 0.0))
    throw std::invalid_argument("sampled loop: T_i must be positive (infinity: none)");
}

std::complex<double> SampledLoop::operator()(double omega) const {
  const Complex z = std::polar(1.0, omega * period_);
  const Complex m = measurement_(omega);
  const double kp = gains_.proportional, ti = gains_.integral_time, t = period_;
  const Complex pd = 1.0 + gains_.derivative_time * (1.0 - 1.0 / z) / t;  // backward difference
  if (!std::isfinite(ti)) return -kp * pd * m;
  // (7.7)-(7.8) with I(z) = T/(z - 1) Z(z) (explicit Euler) and e = -M P.
  return (t - kp * (pd * ti * (z - 1.0) + t) * m) / (ti * (z - 1.0) + t);
}

SampledLoop force_control_loop(const PidGains& gains, double heating_gain, double cooling_rate,
                               double period) {
  if (!(cooling_rate > 0.0)) throw std::invalid_argument("force loop: kappa_c must be positive");
  // The estimator's (7.1): F_T[k] = phi F_T[k-1] + gamma P[k-1].
  const DiscreteThermalForce thermal(heating_gain, cooling_rate, period);
  const double phi = thermal.decay(), gamma = thermal.gain();
  return {gains, period, [phi, gamma, period](double omega) {
            return gamma / (std::polar(1.0, omega * period) - phi);
          }};
}

SampledLoop deflection_control_loop(const PidGains& gains, double heating_gain, double cooling_rate,
                                    const SlsParameters& mechanics,
                                    const EstimatorFilterSettings& filters, double period) {
  if (filters.moving_average < 1 || filters.median < 1 || !(filters.low_pass_cutoff > 0.0) ||
      !(filters.measurement_delay >= 0.0))
    throw std::invalid_argument("deflection loop: invalid filter settings");
  if (!(mechanics.k1 > 0.0 && mechanics.k2 >= 0.0 && mechanics.damping > 0.0))
    throw std::invalid_argument("deflection loop: need k1 > 0, k2 >= 0, c > 0");
  // Muscle at constant force, states (F_T, x_d): (7.1) and the SLS at imposed force, in
  // deviations (models/laws).
  const sls::ForceModeLinearisation muscle = sls::linearise_at_force(mechanics);
  Eigen::Matrix3d augmented = Eigen::Matrix3d::Zero();
  augmented(0, 0) = -cooling_rate;  // (7.1): d F_T / d F_T
  augmented(1, 0) = muscle.dashpot_from_thermal;
  augmented(1, 1) = muscle.dashpot_from_dashpot;
  augmented(0, 2) = heating_gain;  // (7.1): d F_T / d P
  // exp([[A, B], [0, 0]] T) = [[Phi, Gamma], [0, 1]]: the zero-order-hold discretisation.
  const Eigen::Matrix3d exponential = (augmented * period).exp();
  const Eigen::Matrix2d phi = exponential.topLeftCorner<2, 2>();
  const Eigen::Vector2d gamma = exponential.topRightCorner<2, 1>();
  const Eigen::RowVector2d output(muscle.deflection_from_thermal, muscle.deflection_from_dashpot);
  const double pole = std::exp(-2.0 * kPi * filters.low_pass_cutoff * period);
  // The median as a delay of (N - 1)/2 samples, plus the measurement's own delay.
  const double median_delay = 0.5 * (filters.median - 1) + filters.measurement_delay;
  const int averaged = filters.moving_average;
  return {gains, period, [phi, gamma, output, pole, median_delay, averaged, period](double omega) {
            const Complex z = std::polar(1.0, omega * period);
            const Eigen::Matrix2cd resolvent =
                z * Eigen::Matrix2cd::Identity() - phi.cast<Complex>();
            const Complex plant =
                output.cast<Complex>() * resolvent.partialPivLu().solve(gamma.cast<Complex>());
            Complex average = 0.0;
            for (int i = 0; i < averaged; ++i) average += std::pow(z, -i);
            average /= double(averaged);
            const Complex delay = std::polar(1.0, -omega * period * median_delay);
            const Complex low_pass = (1.0 - pole) / (1.0 - pole / z);
            return plant * average * delay * low_pass;
          }};
}

double equilibrium_power(double force, double deflection, double heating_gain, double cooling_rate,
                         const SlsParameters& mechanics) {
  return thermal_force::equilibrium_power(heating_gain, cooling_rate,
                                          sls::rest_thermal_force(mechanics, force, deflection));
}

std::optional<LimitCycle> LimitCyclePrediction::oscillation() const {
  if (verdict != LoopVerdict::limit_cycle || cycles.empty()) return std::nullopt;
  return cycles.front();
}

LimitCyclePrediction predict_limit_cycle(const SampledLoop& loop, const PowerLimits& limits,
                                         double operating_power) {
  const Response response = [&loop](double omega) { return loop(omega); };
  const Response measurement = [&loop](double omega) { return loop.measurement(omega); };
  return conclude(sampled_crossings(response, loop.period()), loop.dc_gain(), limits,
                  operating_power, response, loop.period(), &measurement);
}

LimitCyclePrediction predict_limit_cycle_continuous(const RationalFunction& loop,
                                                    const PowerLimits& limits,
                                                    double operating_power) {
  const Response response = [&loop](double omega) { return loop(Complex(0.0, omega)); };
  auto crossings = real_axis_crossings(response, 1e-8, 1e8, 1.0 / (2.0 * kPi));
  return conclude(std::move(crossings), loop(0.0).real(), limits, operating_power, response, 0.0,
                  nullptr);
}

std::optional<double> proportional_gain_margin(const SampledLoop& loop) {
  auto scaled = [&loop](double factor) {
    PidGains gains = loop.gains();
    gains.proportional *= factor;
    return loop.with_gains(gains);
  };
  constexpr int kPerDecade = 20;
  double previous = 1e-3;
  if (oscillates(scaled(previous))) return previous;
  for (int i = 1; i <= 6 * kPerDecade; ++i) {
    const double factor = 1e-3 * std::pow(10.0, double(i) / kPerDecade);
    if (!oscillates(scaled(factor))) {
      previous = factor;
      continue;
    }
    double low = previous, high = factor;
    for (int iteration = 0; iteration < 60; ++iteration) {
      const double middle = std::sqrt(low * high);
      (oscillates(scaled(middle)) ? high : low) = middle;
    }
    return high;
  }
  return std::nullopt;
}

std::optional<UltimateGain> ultimate_gain(const SampledLoop& loop) {
  const double sign = loop.gains().proportional > 0.0 ? 1.0 : -1.0;
  // P only: G = -K_p M, which reaches 1 first where -sign M is real and largest.
  const Response path = [&loop, sign](double omega) { return -sign * loop.measurement(omega); };
  std::optional<UltimateGain> result;
  double largest = 0.0;
  for (const auto& crossing : sampled_crossings(path, loop.period())) {
    if (crossing.value > largest) {
      largest = crossing.value;
      result = UltimateGain{sign / crossing.value, 1.0 / crossing.frequency};
    }
  }
  return result;
}

}  // namespace tcpmsim
