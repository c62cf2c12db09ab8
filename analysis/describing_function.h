#pragma once

#include <complex>
#include <functional>
#include <optional>
#include <vector>

#include "controllers/pid_controller.h"
#include "models/laws/sls.h"

namespace tcpmsim {

// Stability of the self-sensing control loops against saturation-driven limit cycles by the
// describing-function method (thesis 7.2.5).
//
// The loop. Cut at the saturation (7.9), the linear part maps the applied power P to the
// demanded power P_d: through the muscle model and the estimator into the error e = r - y^, and
// through the back-calculation (7.8), where P enters the integral directly. With a constant
// reference, in deviations from the operating point, e = -M P with M the transfer function from
// P to the estimate y^, and (7.7)-(7.8) give
//     P_d (1 + 1/(T_i s)) = K_p (1 + T_d s + 1/(T_i s)) e + P / (T_i s)
//     G = P_d / P = [1 - K_p M (T_i T_d s^2 + T_i s + 1)] / (T_i s + 1).
// Force control at constant deflection (7.2.5): the deflection estimate is constant, so only
// F_T^ moves, and it comes from the estimator's model (7.1) driven by the commanded power:
// M = kappa_P / (s + kappa_c). Multiplying out,
//     G = [-K_p T_d kappa_P s^2 + (1/T_i - kappa_P K_p) s + (kappa_c - kappa_P K_p)/T_i]
//         / [s^2 + (1/T_i + kappa_c) s + kappa_c / T_i],
// which is the printed (7.10), coefficient for coefficient. The closed loop is P = N(A) P_d,
// so a limit cycle needs G(j w) N(A) = 1: G real and equal to 1/N(A) >= 1 (for the saturation
// N is real, in (0, 1]). The thesis' footnote, made precise: closed through any N in (0, 1],
// the characteristic polynomial is
//     (1 + N K_p T_d kappa_P) s^2 + ((1 - N)/T_i + kappa_c + N K_p kappa_P) s
//         + ((1 - N) kappa_c + N K_p kappa_P) / T_i,
// second order with positive coefficients for every K_p > 0, T_d >= 0: always stable, so no
// harmonic balance exists and continuous time predicts no limit cycle at any gain. (G does
// turn real at w^2 = -X/Y when X = (K_p kappa_P / T_i - kappa_c^2) / T_i and
// Y = K_p kappa_P (1 - T_d (1/T_i + kappa_c)) - 1/T_i differ in sign, e.g. for a PI with
// kappa_c^2 T_i < K_p kappa_P < 1/T_i, but necessarily below 1 there.)
//
// Sampling. The Muscle Drive closes this loop at 20 Hz, and it is a purely discrete loop: the
// estimator's F_T^ at t_k integrates the power commanded at t_{k-1} (one period of delay, exact
// zero-order hold), the integral is explicit Euler, the derivative a backward difference:
//     M(z) = gamma / (z - phi),  phi = exp(-kappa_c T), gamma = (kappa_P/kappa_c)(1 - phi),
//     G(z) = [T - K_p (C(z) T_i (z - 1) + T) M(z)] / (T_i (z - 1) + T),
//     C(z) = 1 + T_d (1 - 1/z) / T.
// Now G(e^{j w T}) is real at the Nyquist frequency too, where the loop can oscillate with
// period 2 samples. That oscillation is exactly a sequence b +- A, whose only components are DC
// and Nyquist, so there the harmonic balance is exact with the saturation's alternation gain
// (saturate_alternation) instead of the sinusoidal describing function. The sampled loop
// changes the verdict for high gains (PI: K_p above ~5.7 kW/N at 20 Hz for Table 7.2), or
// for derivative action (T_d >~ 0.23 s with K_p = 540 W/N), not for the thesis' gains.
//
// Deflection control at constant force (our extension; the thesis has no load model, the
// simulator does): M is the muscle from P to x at constant force ((7.1), then creep of the
// SLS: x = -F_T (c s + k2) / ((k1 + k2) c s + k1 k2)), zero-order-hold sampled, times the
// estimator's filter chain: moving average, the median as a delay of (N - 1)/2 samples (exact
// for the monotone stretches of a slow oscillation; it flattens extrema a little), (7.4) of
// (7.3) linearised (1 when model and plant share lambda's) and the low-pass.
//
// Asymmetric limits. The operating point P* generally does not sit mid-range (1.41 W in
// [0.10, 3.12] W for 0.40 N at 20 mm), so the harmonic balance is solved with the dual-input
// describing function: P_d = b + A sin, and two conditions, the fundamental
// (gain(b, A) = 1/G(w)) and the mean (b - P* = G(1) (mean P - P*), which is the integral's
// balance: the mean of z in (7.8) is zero in a steady oscillation).

// ---- The saturation ----------------------------------------------------------------------

// N(A) of y = clamp(u, -limit, limit) for u = A sin: 1 for A <= limit, else
// (2/pi) (asin(l/A) + (l/A) sqrt(1 - (l/A)^2)).
double saturation_describing_function(double amplitude, double limit);

// Mean output and fundamental gain (fundamental amplitude / A) of a saturation.
struct SaturatedOscillation {
  double mean = 0.0;
  double gain = 0.0;
};
// b + A sin(theta) through clamp(., lower, upper): the dual-input describing function.
SaturatedOscillation saturate_sinusoid(double bias, double amplitude, double lower, double upper);
// The period-2 sequence b + A, b - A, ... through the clamp: exact for a sampled oscillation at
// the Nyquist frequency.
SaturatedOscillation saturate_alternation(double bias, double amplitude, double lower,
                                          double upper);

// ---- Loop transfer functions ---------------------------------------------------------------

// A rational function of s, coefficients in descending powers.
struct RationalFunction {
  std::vector<double> numerator;
  std::vector<double> denominator;
  std::complex<double> operator()(std::complex<double> s) const;
};

// (7.10): P_d / P for force control at constant deflection, continuous time. T_i must be
// finite.
RationalFunction force_loop_transfer_function(const PidGains& gains, double heating_gain,
                                              double cooling_rate);

// The sampled loop P -> P_d at z = e^{j w T}, built from the measurement path M (P -> estimate,
// in the estimate's unit per W) and the controller (7.7)-(7.8) as discretised in
// DiscretePid.
class SampledLoop {
 public:
  using Response = std::function<std::complex<double>(double omega)>;  // M(e^{j omega T})
  SampledLoop(PidGains gains, double period, Response measurement);
  std::complex<double> operator()(double omega) const;  // G(e^{j omega T}), omega [rad/s]
  std::complex<double> measurement(double omega) const { return measurement_(omega); }
  double dc_gain() const { return (*this)(0.0).real(); }  // G(1) = 1 - K_p M(1)
  double period() const { return period_; }
  const PidGains& gains() const { return gains_; }
  SampledLoop with_gains(const PidGains& gains) const { return {gains, period_, measurement_}; }

 private:
  PidGains gains_;
  double period_;
  Response measurement_;
};

SampledLoop force_control_loop(const PidGains& gains, double heating_gain, double cooling_rate,
                               double period);

struct EstimatorFilterSettings {
  int moving_average = 2;
  int median = 15;
  double low_pass_cutoff = 0.111;  // [Hz]; +infinity: none
  // Periods between the deflection and the L* the estimator reads at a sample, beyond the
  // model's x(t_k) at t_k: about 0 for the switched Muscle Drive (L* from the off-phase that
  // just ended), 1 for the averaged one (it measures at the period start, after the estimator
  // has sampled).
  double measurement_delay = 0.0;
};
SampledLoop deflection_control_loop(const PidGains& gains, double heating_gain, double cooling_rate,
                                    const SlsParameters& mechanics,
                                    const EstimatorFilterSettings& filters, double period);

// The equilibrium power (7.1), (7.5) with the dashpot relaxed: F_T = F - k1 x - phi_0 and
// P* = (kappa_c / kappa_P) F_T. For force control F is the reference and x the imposed
// deflection; for deflection control x is the reference and F the imposed force.
double equilibrium_power(double force, double deflection, double heating_gain, double cooling_rate,
                         const SlsParameters& mechanics);

// ---- Prediction ----------------------------------------------------------------------------

struct PowerLimits {
  double min = 0.0;
  double max = 0.0;
};

enum class LoopVerdict {
  stable,       // no harmonic balance: the loop settles (the thesis' claim for its gains)
  limit_cycle,  // a self-sustained oscillation is predicted
  latch_up,     // G(1) > 1: positive feedback at DC (a gain of the wrong sign); the loop runs
                // to a power limit and stays there
  saturated,    // the operating power lies outside the limits: the loop rests at a limit
};

// A harmonic-balance solution. Accuracy: at the Nyquist frequency the balance is exact (a
// period-2 sequence has no other harmonics). Elsewhere the describing function neglects the
// harmonics the saturation makes; they matter as much as the linear part lets them through,
// measured by third_harmonic_ratio = |G(3w)| / |G(w)|. In our deflection loops, with G well
// beyond 1 (1.3 to 2.1), frequency and power fundamental came within 2 % of simulation at
// ratios up to 0.34, while a small T_i, whose back-calculation path passes the harmonics
// (ratio 0.64), put the frequency 11 % off. Just past the onset (G = 1.12) the amplitude is
// sensitive and came 16 % high.
struct LimitCycle {
  double frequency = 0.0;   // [Hz]
  double loop_gain = 0.0;   // G at the crossing, real, = 1/N > 1
  bool at_nyquist = false;  // period-2 oscillation of the sampled loop (exact balance)
  // Whether the solution attracts. Elsewhere than at Nyquist: the largest crossing (Loeb's
  // argument: beyond it 1/N(A) leaves the encircled part of the real axis). At Nyquist the
  // period-2 orbit's stability is decided exactly: perturbations see the saturation's slope
  // alternate between 1 and 0, which couples w and w + pi/T; the orbit attracts if 1 - G_e,
  // G_e(z) = (G(z) + G(-z))/2, has no zero outside the unit circle. When it does not attract the
  // loop still oscillates (its equilibrium is unstable and the saturation bounds it) but
  // irregularly, near the Nyquist frequency and between the limits.
  bool stable = false;
  double third_harmonic_ratio = 0.0;  // |G(3w)| / |G(w)|; 0 at Nyquist (exact)
  double demand_mean = 0.0;           // P_d = b + A sin [W]
  double demand_amplitude = 0.0;      // A [W]
  double power_mean = 0.0;            // mean of P [W]
  double power_low = 0.0;             // extremes of P over the cycle [W]
  double power_high = 0.0;
  double power_fundamental = 0.0;  // amplitude of P's fundamental, A / G [W]
  // Amplitude of the estimate's (the controller input's) fundamental, |M| times the power's
  // [m or N]; 0 for continuous loops, whose M the prediction does not know. For the deflection
  // loop an upper value when the median window spans a good part of the period: the median
  // shaves crests that its pure-delay model keeps (10 % at 15 samples of a 37-sample period,
  // where frequency and power still came within 2 %).
  double estimate_amplitude = 0.0;
};

struct LoopCrossing {
  double frequency = 0.0;  // [Hz]
  double value = 0.0;      // G there (real)
  bool at_nyquist = false;
};

struct LimitCyclePrediction {
  LoopVerdict verdict = LoopVerdict::stable;
  double operating_power = 0.0;         // P* [W]
  double dc_gain = 0.0;                 // G(1)
  std::vector<LoopCrossing> crossings;  // every w > 0 where G is real
  std::vector<LimitCycle> cycles;       // harmonic-balance solutions, largest loop gain first
  // The loop needs G >= 1 somewhere on the real axis to oscillate; this is the factor by which
  // the largest real crossing falls short (> 1: stable). Not a K_p margin (G is affine in K_p
  // with an offset); see proportional_gain_margin.
  double crossing_margin = 0.0;
  // The oscillation to expect: the first cycle (the largest loop gain), if the verdict is
  // limit_cycle; check its `stable` flag for whether it is a regular, periodic one.
  std::optional<LimitCycle> oscillation() const;
};

// The sampled loop's verdict at operating power P* (see equilibrium_power).
LimitCyclePrediction predict_limit_cycle(const SampledLoop& loop, const PowerLimits& limits,
                                         double operating_power);
// The same for a continuous loop G(s) (e.g. the printed (7.10)): crossings for 0 < w < inf,
// sinusoidal describing function throughout.
LimitCyclePrediction predict_limit_cycle_continuous(const RationalFunction& loop,
                                                    const PowerLimits& limits,
                                                    double operating_power);

// The factor m on K_p (T_i, T_d kept) at which the sampled loop starts to oscillate or latch
// up: the smallest m in [1e-3, 1e3] (found by a geometric scan refined by bisection) with a
// real crossing of G at or beyond 1. nullopt if none in that range.
std::optional<double> proportional_gain_margin(const SampledLoop& loop);

// Proportional-only control of the same loop (T_i = inf, T_d = 0), the Ziegler-Nichols
// experiment: the gain magnitude (with the sign of loop's K_p) at which it oscillates, and the
// period. nullopt if no gain of that sign does.
struct UltimateGain {
  double gain = 0.0;    // K_u [W per unit of the estimate]
  double period = 0.0;  // T_u [s]
};
std::optional<UltimateGain> ultimate_gain(const SampledLoop& loop);

}  // namespace tcpmsim
