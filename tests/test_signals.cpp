// Excitation signals: the thesis' multisine and random steps, and the breakpoints all declare.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "analysis/statistics.h"
#include "signals/log_sweep_signal.h"
#include "signals/multisine_signal.h"
#include "signals/periodic_signal.h"
#include "signals/piecewise_constant_signal.h"
#include "signals/random_steps.h"
#include "signals/sequence_signal.h"
#include "sim/signal_reading.h"
#include "tests/support/test_support.h"

using namespace tcpmsim;
using namespace tcpmsim::testing;

namespace {
const double kLow = std::pow(10.0, -2.4), kHigh = std::pow(10.0, -1.1);  // thesis band [Hz]

std::unique_ptr<Signal> signal_from(const std::string& yaml, std::string_view unit, double duration,
                                    std::uint64_t seed = 1) {
  const ConfigNode root =
      ConfigNode::load_text("signal: " + yaml, "signal.yaml", {}, shared_units());
  const KindRegistry kinds = standard_kinds();
  auto signal = read_signal(root.at("signal"), unit, {seed, duration, &kinds, {}});
  root.reject_unknown_keys();
  return signal;
}
}  // namespace

TEST_CASE(
    "Multisine phases follow Schroeder (7.12): phi_i = phi_0 - pi i^2 / N on equally spaced "
    "frequencies") {
  const auto signal = MultisineSignal::schroeder(11, kLow, kHigh, 0.3);
  const auto description = signal.describe();
  const auto& frequencies = description.arrays[1].second;
  const auto& phases = description.arrays[2].second;
  REQUIRE(frequencies.size() == 11);
  CHECK(frequencies.front() == Approx(kLow));
  CHECK(frequencies.back() == Approx(kHigh));
  for (int i = 1; i <= 11; ++i) {
    CHECK(phases[static_cast<std::size_t>(i - 1)] == Approx(0.3 - std::numbers::pi * i * i / 11));
    if (i > 1) {
      CHECK(frequencies[static_cast<std::size_t>(i - 1)] -
                frequencies[static_cast<std::size_t>(i - 2)] ==
            Approx((kHigh - kLow) / 10));
    }
  }
}

TEST_CASE("A Schroeder multisine's crest factor is its peak over the analytic rms sqrt(N/2)") {
  // N unit sines on the harmonics of f0 have, over the period 1 / f0, the mean square N / 2
  // exactly. The peak is found here from (7.11)-(7.12) evaluated directly, on a grid of 1000
  // points per period of the fastest tone.
  const double f0 = 0.01;
  for (int components : {7, 11}) {
    const auto schroeder = MultisineSignal::schroeder(components, f0, f0 * components, 0.0);
    const int points = 1000 * components;
    double peak = 0.0;
    for (int k = 0; k < points; ++k) {
      const double t = static_cast<double>(k) / points / f0;
      double sum = 0.0;
      for (int i = 1; i <= components; ++i) {
        const double phase = -std::numbers::pi * i * i / components;   // (7.12)
        sum += std::sin(2.0 * std::numbers::pi * i * f0 * t + phase);  // (7.11)
      }
      peak = std::max(peak, std::abs(sum));
    }
    const double expected = peak / std::sqrt(components / 2.0);
    INFO(components << " components: expected crest factor " << expected);
    CHECK(schroeder.crest_factor(1.0 / f0) == Approx(expected).epsilon(1e-4));
  }
}

TEST_CASE("Schroeder phases give a lower crest factor than random phases") {
  // Over one full period of a harmonic grid, where crest factors are well defined.
  const double f0 = 0.01;
  for (int components : {7, 11}) {
    const auto schroeder = MultisineSignal::schroeder(components, f0, f0 * components, 0.0);
    const double schroeder_crest = schroeder.crest_factor(1.0 / f0);
    RandomStream stream(42, "crest");
    const auto frequencies = MultisineSignal::equally_spaced(components, f0, f0 * components);
    double random_sum = 0.0;
    const int trials = 200;
    for (int trial = 0; trial < trials; ++trial) {
      std::vector<double> phases;
      for (int i = 0; i < components; ++i)
        phases.push_back(stream.uniform(0.0, 2.0 * std::numbers::pi));
      const MultisineSignal random(0.0, std::vector<double>(frequencies.size(), 1.0), frequencies,
                                   phases);
      random_sum += random.crest_factor(1.0 / f0);
    }
    INFO(components << " components: Schroeder " << schroeder_crest << ", random mean "
                    << random_sum / trials);
    CHECK(schroeder_crest < random_sum / trials);
    CHECK(schroeder_crest <
          2.0);  // a flat multisine of N tones: Schroeder keeps it near sqrt(2)..2
  }
}

TEST_CASE("A multisine scaled to a range spans exactly that range") {
  const auto signal = MultisineSignal::schroeder(7, kLow, kHigh, 1.0).scaled_to(0.10, 3.12, 200.0);
  const auto [low, high] = signal.range(0.0, 200.0);
  CHECK(low == Approx(0.10).epsilon(1e-9));
  CHECK(high == Approx(3.12).epsilon(1e-9));
}

TEST_CASE(
    "Random steps switch with probability 1/(0.5 tau_p f_s), a mean time between switches of "
    "tau_p/2") {
  RandomStepsSettings settings;
  settings.low = 0.1, settings.high = 3.12, settings.process_time_constant = 20.0;
  settings.sample_rate = 20.0, settings.duration = 2e5;
  RandomStream stream(7, "gbn");
  const auto steps = make_random_steps(settings, stream);
  const auto& times = steps->times();
  REQUIRE(times.size() > 1000);
  const double mean = (times.back() - times.front()) / static_cast<double>(times.size() - 1);
  // Geometric waiting times: standard deviation about the mean, so the standard error is
  // mean / sqrt(n). Allow four standard errors.
  const double standard_error = 10.0 / std::sqrt(static_cast<double>(times.size()));
  CHECK(std::abs(mean - 10.0) < 4.0 * standard_error);
  // Values stay in range and reach both limits after scaling; steps obey the 25 % rule.
  const auto [low, high] = steps->range(0.0, settings.duration);
  CHECK(low == Approx(0.1));
  CHECK(high == Approx(3.12));
}

TEST_CASE("Random-step sizes are uniform on [0, a quarter of the range] before scaling (7.13)") {
  RandomStepsSettings settings;
  settings.low = 0.0, settings.high = 1.0, settings.process_time_constant = 2.0;
  settings.sample_rate = 10.0, settings.duration = 2e4, settings.scale_to_range = false;
  RandomStream stream(3, "sizes");
  const auto steps = make_random_steps(settings, stream);
  std::vector<double> sizes;
  double previous = 0.5;
  long outside = 0;
  for (double value : steps->values()) {
    if (value < 0.0 || value > 1.0) ++outside;
    sizes.push_back(std::abs(value - previous));
    previous = value;
  }
  CHECK(outside == 0);
  REQUIRE(sizes.size() > 10000);
  // A step reversed at a bound keeps its size, so every size is a draw of U(0, 0.25): mean
  // 0.125, standard deviation 0.25 / sqrt(12). Four standard errors on the mean, and the
  // Kolmogorov-Smirnov distance to U(0, 0.25) under its 0.1 % critical value 1.95 / sqrt(n).
  const double n = static_cast<double>(sizes.size());
  const double mean = analysis::mean(sizes);
  CHECK(std::abs(mean - 0.125) < 4.0 * (0.25 / std::sqrt(12.0)) / std::sqrt(n));
  std::sort(sizes.begin(), sizes.end());
  CHECK(sizes.back() <= 0.25);
  double distance = 0.0;
  for (std::size_t i = 0; i < sizes.size(); ++i) {
    const double cdf = sizes[i] / 0.25;
    distance = std::max({distance, std::abs(cdf - static_cast<double>(i) / n),
                         std::abs(cdf - static_cast<double>(i + 1) / n)});
  }
  CHECK(distance < 1.95 / std::sqrt(n));
}

TEST_CASE("Random signals are reproducible from the seed and differ between seeds and keys") {
  const std::string yaml =
      "{type: random_steps, range: [0 W, 1 W], process_time_constant: 5 s, sample_rate: 10 Hz}";
  const auto a = signal_from(yaml, "W", 500.0, 11), b = signal_from(yaml, "W", 500.0, 11);
  const auto c = signal_from(yaml, "W", 500.0, 12);
  CHECK(a->describe().arrays == b->describe().arrays);
  CHECK(a->describe().arrays != c->describe().arrays);
}

TEST_CASE("Every signal declares its discontinuities as breakpoints") {
  const auto steps =
      signal_from("{type: steps, initial: 0 W, times: [1 s, 2.5 s], values: [1 W, 0 W]}", "W", 10);
  CHECK(steps->next_breakpoint_after(0.0) == 1.0);
  CHECK(steps->next_breakpoint_after(1.0) == 2.5);
  CHECK(steps->next_breakpoint_after(2.5) == kNoBreakpoint);
  CHECK(steps->value(1.0) == 1.0);  // right-continuous
  const auto ramp =
      signal_from("{type: ramp, start_time: 2 s, end_time: 4 s, from: 1 mm, to: 3 mm}", "m", 10);
  CHECK(ramp->next_breakpoint_after(0.0) == 2.0);
  CHECK(ramp->next_breakpoint_after(2.0) == 4.0);
  CHECK(ramp->value(3.0) == Approx(0.002));
  const auto sweep = signal_from(
      "{type: log_sweep, offset: 0 N, amplitude: 1 N, band: [0.01 Hz, 1 Hz], duration: 100 s}", "N",
      200);
  CHECK(sweep->next_breakpoint_after(10.0) == 100.0);
  const auto sequence = signal_from(
      "{type: sequence, segments: [{duration: 5 s, signal: 1 W}, {signal: {type: steps, initial: 2 "
      "W, times: [1 s], values: [3 W]}}]}",
      "W", 10);
  CHECK(sequence->next_breakpoint_after(0.0) == 5.0);
  CHECK(sequence->next_breakpoint_after(5.0) == 6.0);
  CHECK(sequence->value(5.5) == 2.0);
  CHECK(sequence->value(6.0) == 3.0);
}

TEST_CASE("A shifted breakpoint that rounds onto the query time is skipped, not returned") {
  // 200 + 0.05 rounds so that (200.05 - 200) < 0.05: a naive shift would return 200.05 again.
  std::vector<SequenceSignal::Segment> segments;
  segments.push_back({0.0, std::make_unique<PiecewiseConstantSignal>(0.0, std::vector<double>{},
                                                                     std::vector<double>{})});
  segments.push_back(
      {200.0, std::make_unique<PiecewiseConstantSignal>(0.0, std::vector<double>{0.05, 0.1},
                                                        std::vector<double>{1.0, 2.0})});
  const SequenceSignal sequence(std::move(segments));
  const double first = sequence.next_breakpoint_after(199.0);
  CHECK(first == 200.0);
  const double second = sequence.next_breakpoint_after(first);
  CHECK(second > first);
  CHECK(sequence.next_breakpoint_after(second) > second);
}

TEST_CASE("A staircase holds each level and moves at the configured rate") {
  const auto stairs = signal_from(
      "{type: staircase, levels: [2 mm, 4 mm, 2 mm], hold: 15 s, rate: 15 mm/min}", "m", 100);
  CHECK(stairs->value(14.9) == Approx(0.002));
  CHECK(stairs->value(19.0) == Approx(0.003));  // halfway through the 8 s move
  CHECK(stairs->value(30.0) == Approx(0.004));
  CHECK(stairs->value(46.0) == Approx(0.002));  // 15 + 8 + 15 + 8 = 46 s
}

TEST_CASE("A periodic signal restarts its clock every period") {
  const PeriodicSignal periodic(10.0, std::make_unique<PiecewiseConstantSignal>(
                                          0.0, std::vector<double>{4.0}, std::vector<double>{1.0}));
  CHECK(periodic.value(3.0) == 0.0);
  CHECK(periodic.value(24.0) == 1.0);
  CHECK(periodic.next_breakpoint_after(5.0) == 10.0);
  CHECK(periodic.next_breakpoint_after(10.0) == 14.0);
}

TEST_CASE(
    "A logarithmic sweep's instantaneous frequency grows exponentially from f_start to f_end") {
  const LogSweepSignal sweep(0.0, 1.0, 1.0, 100.0, 100.0);
  CHECK(sweep.instantaneous_frequency(0.0) == Approx(1.0));
  CHECK(sweep.instantaneous_frequency(50.0) == Approx(10.0));
  CHECK(sweep.instantaneous_frequency(100.0) == Approx(100.0));
  // Zero crossings over [50, 52] s count twice the cycles, the integral of f(t) dt.
  const double rate = std::log(100.0);
  const double cycles =
      100.0 / rate * (std::exp(52.0 * rate / 100.0) - std::exp(50.0 * rate / 100.0));
  int crossings = 0;
  for (int k = 0; k < 200000; ++k) {
    const double t0 = 50.0 + k * 1e-5, t1 = t0 + 1e-5;
    if ((sweep.value(t0) < 0) != (sweep.value(t1) < 0)) ++crossings;
  }
  CHECK(std::abs(crossings - 2.0 * cycles) <= 1.0);
}
