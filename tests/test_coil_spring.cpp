// The lumped-mass coil spring (thesis ch. 4) against the continuum, its own linear model, and
// the published Table 4.2.
#include <catch2/catch.hpp>

#include <cmath>
#include <complex>
#include <numbers>

#include "analysis/spring_forces.h"
#include "analysis/spring_modes.h"
#include "models/coil_spring_chain.h"
#include "models/inductance/rosa.h"
#include "tests/support/test_support.h"

using namespace tcpmsim;
using namespace tcpmsim::testing;

namespace {
// Spring S_T of Table 4.1.
constexpr double kMass = 0.065, kStiffness = 760.0, kRestLength = 0.104;

std::string spring_yaml(const std::string& extra = "") {
  return R"(
scenario: {name: spring, duration: 0.5 s}
output: {rate: 10 kHz}
solver: {method: adams, rtol: 1.0e-9}
spring:
  windings: 52
  rest_length: 104 mm
  mass: 65 g
  stiffness: 760 N/m
  first_end: 0 mm
  second_end: 230 mm
  inductance: {coil_radius: 8 mm, wire_diameter: 2 mm, operating_range: [196 mm, 264 mm]}
)" + extra;
}

const CoilSpringChain& chain_of(const Scenario& scenario) {
  const auto* chain = scenario.system->find<const CoilSpringChain>();
  if (!chain) throw std::logic_error("no chain");
  return *chain;
}

double rms(const std::vector<double>& a, const std::vector<double>& b, std::size_t from) {
  double sum = 0.0;
  for (std::size_t i = from; i < a.size(); ++i) sum += (a[i] - b[i]) * (a[i] - b[i]);
  return std::sqrt(sum / static_cast<double>(a.size() - from));
}
}  // namespace

TEST_CASE(
    "A statically stretched chain has the series stiffness k, uniform windings, and stays at "
    "rest") {
  const Trace trace = simulate(spring_yaml());
  const double force = kStiffness * (0.230 - kRestLength);
  // Position errors of rtol |xi| become force errors through the end elements' 2Nk.
  const double force_tolerance = 10 * 1e-9 * 0.230 * 2 * 52 * kStiffness;
  for (std::size_t i = 0; i < trace.time.size(); i += 100) {
    REQUIRE(trace["spring/input_force"][i] == Approx(force).margin(force_tolerance));
    REQUIRE(trace["spring/output_force"][i] == Approx(force).margin(force_tolerance));
    REQUIRE(trace["spring/winding_01"][i] == Approx(0.5 * 0.230 / 52).margin(1e-9));
    REQUIRE(trace["spring/winding_52"][i] == Approx(0.230 - 0.5 * 0.230 / 52).margin(1e-9));
  }
}

TEST_CASE(
    "Inductance sensing reproduces F_x at the preload and errs elsewhere by the curvature of "
    "(4.13), as Rosa's independent formula (2.7)-(2.10) predicts") {
  // Rosa's round-wire correction of Nagaoka's current sheet is a different route to the same
  // inductance as the chain's ring sum (2.13): the two differ by how each treats the wire, 0.1-0.2
  // % over this range. (The misprinted self-term gmd of (4.10), or any slip of the sum, would
  // move L by several per cent.)
  const auto rosa = [](double length) {
    return inductance::rosa_inductance({8e-3, length, 52.0, 2e-3});
  };
  const Trace at_preload = simulate(spring_yaml());
  CHECK(at_preload["spring/inductance"].front() == Approx(rosa(0.230)).epsilon(2e-3));
  CHECK(at_preload["spring/inductance_force"].front() ==
        Approx(at_preload["spring/deflection_force"].front()).epsilon(1e-9));

  // (4.13) fitted to Rosa's L over the operating range, through the preload point: 1/l =
  // alpha L + beta, alpha = sum dL d(1/l) / sum dL^2 about the preload (25 lengths).
  const double preload = 0.230, shortest = 0.196, longest = 0.264;
  double covariance = 0.0, variance = 0.0;
  for (int k = 0; k < 25; ++k) {
    const double length = shortest + (longest - shortest) * k / 24.0;
    const double dL = rosa(length) - rosa(preload);
    covariance += dL * (1.0 / length - 1.0 / preload);
    variance += dL * dL;
  }
  const double alpha = covariance / variance, beta = 1.0 / preload - alpha * rosa(preload);
  // Held statically at other lengths, the spring's inductance-based force misses k (l - l0) by
  // what the straight line in 1/L cannot follow: with Rosa's L, 760 N/m (1/(alpha L + beta) - l),
  // -0.20 N at 196 mm, -0.11 N at 247 mm, -0.41 N at 264 mm. A wrong slope alpha moves these
  // by 68 mm x 760 N/m = 52 N per unit of relative error.
  for (const double length : {0.196, 0.213, 0.247, 0.264}) {
    INFO("held at " << length * 1e3 << " mm");
    const Trace held = simulate(
        spring_yaml(), {"scenario.duration=10 ms", "spring.second_end=" + number(length) + " m",
                        "spring.inductance.preload_length=230 mm"});
    const double predicted_error = kStiffness * (1.0 / (alpha * rosa(length) + beta) - length);
    const double error =
        held["spring/inductance_force"].front() - held["spring/deflection_force"].front();
    CHECK(held["spring/deflection_force"].front() ==
          Approx(kStiffness * (length - kRestLength)).epsilon(1e-9));
    CHECK(error == Approx(predicted_error).epsilon(0.06));
  }
}

TEST_CASE("Clamped eigenfrequencies approach n pi sqrt(k/m) within the lumping's dispersion") {
  Scenario scenario = scenario_from_text(spring_yaml());
  const auto frequencies = clamped_eigenfrequencies(chain_of(scenario));
  REQUIRE(frequencies.size() == 52);
  for (int n = 1; n <= 5; ++n) {
    const double continuum = n * std::numbers::pi * std::sqrt(kStiffness / kMass);  // (4.3)
    // A lumped chain underestimates mode n by about (n pi / N)^2 / 24 (second-order dispersion).
    const double dispersion = std::pow(n * std::numbers::pi / 52.0, 2) / 24.0;
    INFO("mode " << n << ": " << frequencies[static_cast<std::size_t>(n - 1)] << " rad/s vs "
                 << continuum);
    CHECK(frequencies[static_cast<std::size_t>(n - 1)] < continuum);
    CHECK(1.0 - frequencies[static_cast<std::size_t>(n - 1)] / continuum < 2.0 * dispersion);
  }
}

TEST_CASE("The force transmissibility follows F_o/F_i = 1/cos(omega tau) (4.1) from 1 to 200 Hz") {
  Scenario scenario = scenario_from_text(spring_yaml());
  const auto& chain = chain_of(scenario);
  const double tau = std::sqrt(kMass / kStiffness);
  for (int hz = 1; hz <= 200; ++hz) {
    const double omega = 2.0 * std::numbers::pi * hz;
    // Compare 1/T, which is finite where T has its poles (omega tau = pi/2, 3 pi/2, ...).
    const std::complex<double> inverse = 1.0 / force_transmissibility(chain, omega);
    const double phase_error = omega * tau * std::pow(omega * tau / 52.0, 2) / 24.0;  // dispersion
    INFO(hz << " Hz");
    REQUIRE(std::abs(inverse.imag()) < 1e-9);  // undamped: in phase or in antiphase
    REQUIRE(std::abs(inverse.real() - std::cos(omega * tau)) < 2.0 * phase_error + 1e-9);
  }
}

TEST_CASE("The simulated chain settles to the frequency response of its linear model") {
  // With 5 % damping the start-up transient decays; then F_o/F_i is the matrix prediction.
  const double hz = 20.0;
  Scenario scenario = scenario_from_text(
      spring_yaml(),
      {"scenario.duration=3 s", "output.rate=20 kHz", "spring.damping_ratio=0.05",
       "spring.first_end={type: sine, offset: 0 mm, amplitude: 0.5 mm, frequency: 20 Hz}"});
  const Trace trace = simulate(scenario);
  // Sine fits over exactly the last 20 periods, [2 s, 3 s), about the mean (the static preload).
  auto fit = [&](const std::vector<double>& values) {
    std::vector<double> window;
    std::vector<double> phases;
    for (std::size_t i = 0; i < trace.time.size(); ++i) {
      if (trace.time[i] < 2.0 || trace.time[i] >= 3.0 - 1e-9) continue;
      window.push_back(values[i]);
      phases.push_back(2.0 * std::numbers::pi * hz * trace.time[i]);
    }
    double mean = 0.0;
    for (double v : window) mean += v / static_cast<double>(window.size());
    double c = 0, s = 0;
    for (std::size_t i = 0; i < window.size(); ++i) {
      c += (window[i] - mean) * std::cos(phases[i]), s += (window[i] - mean) * std::sin(phases[i]);
    }
    return std::complex<double>(s, c) * (2.0 / static_cast<double>(window.size()));
  };
  const std::complex<double> simulated =
      fit(trace["spring/output_force"]) / fit(trace["spring/input_force"]);
  const std::complex<double> predicted =
      force_transmissibility(chain_of(scenario), 2.0 * std::numbers::pi * hz);
  CHECK(std::abs(simulated - predicted) < 1e-3 * std::abs(predicted));
}

TEST_CASE("After a heel strike the end forces ring with the continuum's amplitude v sqrt(k m)") {
  // A uniformly moving spring stopped at both ends: each end sees a square wave of amplitude
  // v sqrt(k m) about F_x (wave impedance), so the RMS difference is v sqrt(k m).
  const Trace trace =
      simulate(spring_yaml(), {"scenario.duration=1 s", "output.rate=50 kHz",
                               "spring.initial_velocity={profile: uniform, value: 0.25 m/s}"});
  const double expected = 0.25 * std::sqrt(kStiffness * kMass);
  const std::size_t from = trace.time.size() * 3 / 4;
  CHECK(rms(trace["spring/input_force"], trace["spring/deflection_force"], from) ==
        Approx(expected).epsilon(0.01));
  CHECK(rms(trace["spring/output_force"], trace["spring/deflection_force"], from) ==
        Approx(expected).epsilon(0.01));
}

TEST_CASE(
    "Extension and contraction end stops give equal end-force deviations in the linear model") {
  // The chain is linear about any length, and the two cases mirror each other's velocities.
  // (F_L differs: the inductance's sensitivity depends on the length.)
  const auto rows = run_spring_forces({source_path("configs/ch4/st_end_stop_max.yaml"),
                                       source_path("configs/ch4/st_end_stop_min.yaml")},
                                      0.25, 2, shared_units());
  for (std::size_t k = 0; k < 2; ++k)
    CHECK(rows[0].simulated.rms[k] == Approx(rows[1].simulated.rms[k]).epsilon(1e-6));
}

TEST_CASE("Table 4.2: S_T heel strike and resonance reproduce the published RMS differences") {
  const auto rows = run_spring_forces({source_path("configs/ch4/st_heel_strike.yaml"),
                                       source_path("configs/ch4/st_harmonic_first.yaml")},
                                      0.25, 2, shared_units());
  REQUIRE(rows[0].thesis.has_value());
  for (std::size_t k = 0; k < 3; ++k) {
    INFO("sensor " << k);
    CHECK(std::abs(rows[0].simulated.rms[k] - rows[0].thesis->rms[k]) < 0.011);  // printed to 0.01
  }
  // At omega_1 the growth of the resonance over the window makes the RMSD sensitive to the
  // exact lumped eigenfrequency; 0.5 % agreement.
  for (std::size_t k = 0; k < 3; ++k)
    CHECK(rows[1].simulated.rms[k] == Approx(rows[1].thesis->rms[k]).epsilon(0.005));
}

TEST_CASE("Non-uniform windings bias the inductance-based force low (thesis 4.6)") {
  const auto rows = run_spring_forces({source_path("configs/ch4/st_harmonic_first.yaml")}, 0.25, 1,
                                      shared_units());
  // A vibrating spring's inductance exceeds the uniform one, so F_L never rises above F_x by
  // more than rounding, while its RMS difference is substantial.
  CHECK(rows[0].simulated.maximum[2] < 0.005);
  CHECK(rows[0].simulated.rms[2] > 0.2);
}

TEST_CASE("Spring-force analysis results do not depend on the number of threads") {
  const std::vector<std::string> configs{source_path("configs/ch4/sa_end_stop_max.yaml"),
                                         source_path("configs/ch4/sa_heel_strike.yaml")};
  const auto one = run_spring_forces(configs, 0.25, 1, shared_units());
  const auto two = run_spring_forces(configs, 0.25, 2, shared_units());
  for (std::size_t r = 0; r < one.size(); ++r) {
    CHECK(one[r].simulated.rms == two[r].simulated.rms);
    CHECK(one[r].simulated.maximum == two[r].simulated.maximum);
  }
}

TEST_CASE("The winding chain's Jacobian is banded, and BDF with the band solver reproduces Adams") {
  Scenario scenario = scenario_from_text(spring_yaml());
  const SparsityPattern pattern = scenario.system->jacobian_pattern();
  CHECK(pattern.size == 104);
  CHECK(pattern.lower_bandwidth() <= 3);  // interleaved (position, velocity) per winding
  CHECK(pattern.upper_bandwidth() <= 3);
  const std::vector<std::string> heel{
      "scenario.duration=0.2 s", "spring.initial_velocity={profile: uniform, value: 0.25 m/s}"};
  auto with = [&](std::vector<std::string> extra) {
    extra.insert(extra.end(), heel.begin(), heel.end());
    return simulate(spring_yaml(), extra);
  };
  const Trace adams = with({"solver.rtol=1e-10"});
  const Trace band = with({"solver.method=bdf", "solver.linear_solver=band", "solver.rtol=1e-10"});
  // Both resolve the 1.8 kHz modes; forces agree to a few mN of the 95.8 N preload.
  CHECK(max_abs_difference(adams["spring/input_force"], band["spring/input_force"]) < 5e-3);
  CHECK(band.statistics.jacobian_evaluations > 0);
}
