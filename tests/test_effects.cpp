// The effect terms the discovery workflow attaches (thermal_lag, heat_sink, hysteresis,
// nonlinear_stiffness), each against its analytic solution.
#include <catch2/catch.hpp>

#include <Eigen/Dense>

#include <cmath>

#include "models/effects/free_convection.h"
#include "tests/support/test_support.h"

using namespace tcpmsim;
using namespace tcpmsim::testing;

namespace {

constexpr double kAmbient = 293.15, kCapacity = 0.5, kConductance = 0.05;  // the test muscle
constexpr double kWireCapacity = 0.05, kWireConductance = 0.02;            // J/K, W/K

// The rise above ambient of a linear network of two nodes, dy/dt = A y + f, after a step of
// the forcing f at t_s, both nodes at ambient before it; solved through the eigenvectors of
// A's (real, distinct) eigenvalues. Returns the first node's temperature.
double step_response(const Eigen::Matrix2d& a, const Eigen::Vector2d& forcing, double t,
                     double step_time) {
  if (t <= step_time) return kAmbient;
  const Eigen::Vector2d steady = -a.inverse() * forcing;  // rises above ambient
  const Eigen::EigenSolver<Eigen::Matrix2d> solver(a);
  const Eigen::Matrix2d vectors = solver.eigenvectors().real();
  const Eigen::Vector2d values = solver.eigenvalues().real();
  const Eigen::Vector2d weights = vectors.inverse() * (-steady);
  Eigen::Vector2d rise = steady;
  for (int k = 0; k < 2; ++k)
    rise += weights(k) * std::exp(values(k) * (t - step_time)) * vectors.col(k);
  return kAmbient + rise(0);
}

// The wire before the polymer after a power step P:
//   C dT/dt = G_w (T_w - T) - hA (T - T_amb),   C_w dT_w/dt = P - G_w (T_w - T).
double two_node_temperature(double t, double step_time, double power) {
  Eigen::Matrix2d a;
  a << -(kWireConductance + kConductance) / kCapacity, kWireConductance / kCapacity,
      kWireConductance / kWireCapacity, -kWireConductance / kWireCapacity;
  return step_response(a, Eigen::Vector2d(0.0, power / kWireCapacity), t, step_time);
}

const std::string kWire =
    "muscle.effects=[{type: thermal_lag, name: wire, heat_capacity: 0.05 J/K, conductance: 0.02 "
    "W/K}]";
const std::string kPowerStep =
    "drive.power={type: steps, initial: 0 W, times: [10 s], values: [1.5 W]}";

// A triangle of deflection rising from 20 to 26 mm and back, `period` long, for `periods`, with
// 200 samples per half period.
std::vector<std::string> triangle(double period, int periods) {
  const double half = period / 2.0;
  return {"scenario.duration=" + number(period * periods) + " s",
          "load.deflection={type: periodic, period: " + number(period) +
              " s, signal: {type: piecewise_linear, times: [0 s, " + number(half) + " s, " +
              number(period) + " s], values: [20 mm, 26 mm, 20 mm]}}",
          "output.rate=" + number(200.0 / half) + " Hz"};
}

}  // namespace

TEST_CASE("A thermal lag makes the polymer follow the two-node network's analytic response") {
  const Trace trace = simulate(physical_muscle_yaml(), {kWire, kPowerStep});
  double worst = 0.0;
  for (std::size_t i = 0; i < trace.time.size(); ++i) {
    worst = std::max(worst, std::abs(trace["muscle/temperature"][i] -
                                     two_node_temperature(trace.time[i], 10.0, 1.5)));
  }
  INFO("worst error " << worst << " K");
  CHECK(worst <= allowed(1e-8, 30.0) + 50.0 * 1e-6);  // rtol on the rise, the nodes' atol
  // The wire holds the power at first: the polymer starts with zero slope, unlike one node.
  const std::size_t just_after = 101;  // 10.1 s at 10 Hz
  const double single_node_rise = 1.5 / kCapacity * 0.1;
  CHECK(trace["muscle/temperature"][just_after] - kAmbient < 0.1 * single_node_rise);
  // The steady state is the single node's, T_amb + P/hA.
  const Trace long_run =
      simulate(physical_muscle_yaml(), {kWire, kPowerStep, "scenario.duration=400 s"});
  CHECK(long_run["muscle/temperature"].back() ==
        Approx(kAmbient + 1.5 / kConductance).epsilon(1e-7));
}

TEST_CASE(
    "Hysteresis follows Dahl's branch z = F_h - (F_h - z0) exp(-k_h dx/F_h), whatever the speed") {
  const double k_h = 20.0, f_h = 0.005;  // 20 mN/mm, 5 mN
  const std::string effect =
      "muscle.effects=[{type: hysteresis, name: friction, stiffness: 20 mN/mm, force: 5 mN, "
      "follower_time: 1 ms}]";
  auto loop = [&](double period) {
    auto overrides = triangle(period, 2);
    overrides.push_back(effect);
    return simulate(physical_muscle_yaml(), overrides);
  };
  for (double period : {20.0, 200.0}) {
    const Trace trace = loop(period);
    const auto& x = trace["load/deflection"];
    const auto& z = trace["muscle/friction/force"];
    // On the second period's rising branch (20 mm up to 26 mm, after the first period's fall),
    // z starts from the value the fall left, near -F_h, and follows the exponential branch.
    const std::size_t start = trace.time.size() / 2;  // t = 1 period
    const double x0 = x[start], z0 = z[start];
    double worst = 0.0;
    for (std::size_t i = start; i < start + trace.time.size() / 4 - 1; ++i) {
      const double branch = f_h - (f_h - z0) * std::exp(-k_h * (x[i] - x0) / f_h);
      worst = std::max(worst, std::abs(z[i] - branch));
    }
    // The follower lags the deflection by v tau_f, and the branch rises with slope up to 2 k_h
    // after a reversal (at z = -F_h), which the follower also turns tau_f late: the error is
    // first order in v tau_f, here 3 k_h v tau_f.
    const double lag = 12e-3 / period * 1e-3;  // v tau_f [m]
    INFO("period " << period << " s: z0 = " << z0 << " N, worst " << worst << " N");
    CHECK(z0 == Approx(-f_h).epsilon(0.01));
    CHECK(worst <= 4.0 * k_h * lag + allowed(1e-8, f_h));
  }
  // The loop in the force-deflection plane is the same at both speeds (rate independence), to
  // the faster run's follower lag.
  const Trace slow = loop(200.0), fast = loop(20.0);
  CHECK(max_abs_difference(slow["muscle/friction/force"], fast["muscle/friction/force"]) <=
        4.0 * k_h * 12e-3 / 20.0 * 1e-3 + allowed(1e-8, f_h));
}

TEST_CASE("A nonlinear stiffness adds k_n w softplus((x - x_k)/w) to the muscle's force") {
  const double k_n = 10.0, knee = 0.024, width = 0.001;  // 10 mN/mm past 24 mm, over 1 mm
  auto softplus_force = [&](double x) {
    return k_n * width * std::log1p(std::exp((x - knee) / width));
  };
  const auto overrides = triangle(400.0, 1);
  auto with = overrides;
  with.push_back(
      "muscle.effects=[{type: nonlinear_stiffness, name: knee, stiffness: 10 mN/mm, "
      "knee_deflection: 24 mm, knee_width: 1 mm, follower_time: 1 ms}]");
  const Trace bare = simulate(physical_muscle_yaml(), overrides);
  const Trace knee_trace = simulate(physical_muscle_yaml(), with);
  double worst = 0.0, largest = 0.0;
  for (std::size_t i = 0; i < bare.time.size(); ++i) {
    const double added = knee_trace["muscle/force"][i] - bare["muscle/force"][i];
    const double expected = softplus_force(bare["load/deflection"][i]);
    largest = std::max(largest, expected);
    worst = std::max(worst, std::abs(added - expected));
  }
  INFO("largest added force " << largest << " N, worst error " << worst << " N");
  CHECK(largest > 0.015);
  // The linearisation about the follower errs by F'' (v tau_f)^2 / 2 < k_n / (4 w) (3e-8 m)^2
  // / 2, about 1e-12 N: what remains is the solver's.
  CHECK(worst <= allowed(1e-8, largest));
}

TEST_CASE("A heating lag delays a share of the power by a first-order lag") {
  // Power step P at t_s into one node: C dT/dt = (1 - a) P + a P_l - hA (T - T_amb) with
  // tau dP_l/dt = P - P_l. With lambda = hA / C and mu = 1 / tau, the rise is
  //   T - T_amb = P/hA [1 - e^(-lambda s)] - a P/C [e^(-mu s) - e^(-lambda s)] / (lambda - mu).
  const double share = 0.6, tau = 3.0, power = 1.5;
  const double lambda = kConductance / kCapacity, mu = 1.0 / tau;
  auto rise = [&](double s) {
    if (s <= 0) return 0.0;
    return power / kConductance * (1 - std::exp(-lambda * s)) -
           share * power / kCapacity * (std::exp(-mu * s) - std::exp(-lambda * s)) / (lambda - mu);
  };
  const Trace trace = simulate(physical_muscle_yaml(),
                               {kPowerStep,
                                "muscle.effects=[{type: heating_lag, name: wire, share: 0.6, "
                                "time_constant: 3 s}]"});
  double worst = 0.0;
  for (std::size_t i = 0; i < trace.time.size(); ++i)
    worst = std::max(
        worst, std::abs(trace["muscle/temperature"][i] - kAmbient - rise(trace.time[i] - 10.0)));
  INFO("worst error " << worst << " K");
  CHECK(worst <= allowed(1e-8, 30.0) + 50.0 * 1e-6);
}

TEST_CASE("A heat sink beside the polymer follows the two-node network's analytic response") {
  // A body of time constant tau_s = C_s / G_s beside the polymer, after a power step P:
  //   C dT/dt = P - hA (T - T_amb) - G_s (T - T_s),   tau_s dT_s/dt = T - T_s.
  const double conductance = 0.03, tau = 15.0, power = 1.5;
  Eigen::Matrix2d a;
  a << -(conductance + kConductance) / kCapacity, conductance / kCapacity, 1.0 / tau, -1.0 / tau;
  const Eigen::Vector2d forcing(power / kCapacity, 0.0);
  for (const std::string given : {"time_constant: 15 s", "heat_capacity: 0.45 J/K"}) {
    const Trace trace = simulate(
        physical_muscle_yaml(),
        {kPowerStep,
         "muscle.effects=[{type: heat_sink, name: clamp, conductance: 0.03 W/K, " + given + "}]"});
    double worst = 0.0;
    for (std::size_t i = 0; i < trace.time.size(); ++i)
      worst = std::max(worst, std::abs(trace["muscle/temperature"][i] -
                                       step_response(a, forcing, trace.time[i], 10.0)));
    INFO(given << ": worst error " << worst << " K");
    CHECK(worst <= allowed(1e-8, 30.0) + 50.0 * 1e-6);
  }
  // It slows the rise, yet the steady state is the single node's, T_amb + P/hA: the body has
  // caught up and takes nothing.
  const Trace bare = simulate(physical_muscle_yaml(), {kPowerStep});
  const Trace sunk = simulate(
      physical_muscle_yaml(),
      {kPowerStep, "scenario.duration=600 s",
       "muscle.effects=[{type: heat_sink, name: clamp, conductance: 0.03 W/K, time_constant: "
       "15 s}]"});
  CHECK(sunk["muscle/temperature"][150] < bare["muscle/temperature"][150] - 1.0);  // at 15 s
  CHECK(sunk["muscle/temperature"].back() == Approx(kAmbient + power / kConductance).epsilon(1e-7));
}

TEST_CASE("An effect at zero size leaves the muscle as it was (discover's nested start)") {
  // The forces of the muscle under a deflection triangle and a power step: every effect that
  // discover's candidates start at zero size carries exactly nothing there. Its extra states
  // change the solver's steps, so the forces agree to the solver's tolerance, not bit for bit.
  auto overrides = triangle(40.0, 2);
  overrides.push_back("drive.power={type: steps, initial: 0 W, times: [20 s], values: [1.5 W]}");
  const Trace bare = simulate(physical_muscle_yaml(), overrides);
  for (const std::string effect :
       {"{type: maxwell_branch, name: b, stiffness: 0 N/m, time_constant: 20 s}",
        "{type: hysteresis, name: h, stiffness: 0 N/m, radius: 1 mm}",
        "{type: free_convection, name: c, conductance: 0 W/K, reference_difference: 50 K, "
        "exponent: 1.4}",
        "{type: nonlinear_stiffness, name: n, stiffness: 0 N/m, knee_deflection: 24 mm, "
        "knee_width: 1 mm}",
        "{type: thermal_softening, name: s, reference_stiffness: 0 N/m, "
        "temperature_coefficient: 0.01 1/K, reference_temperature: 20 degC}",
        "{type: heating_lag, name: l, share: 0, time_constant: 3 s}",
        "{type: heat_sink, name: k, conductance: 0 W/K, time_constant: 10 s}",
        "{type: ratchet, name: r, rate: 0 N/(K*s), threshold: 25 degC}",
        "{type: heating_convection, name: f, conductance: 0 W/K, reference_power: 1.5 W}",
        "{type: heating_convection, name: g, conductance: 0 W/K, switch_power: 1 W, "
        "switch_width: 0.2 W, time_constant: 2 s}"}) {
    auto with = overrides;
    with.push_back("muscle.effects=[" + effect + "]");
    const Trace trace = simulate(physical_muscle_yaml(), with);
    INFO(effect);
    CHECK(max_abs_difference(trace["muscle/force"], bare["muscle/force"]) <= allowed(1e-8, 0.3));
    CHECK(max_abs_difference(trace["muscle/temperature"], bare["muscle/temperature"]) <=
          allowed(1e-8, 30.0));
  }
}

TEST_CASE("A stiffness slope and bend change the muscle's stiffness with temperature, from zero") {
  // Under an imposed deflection the added term is F_s = (beta + gamma dT) dT x, dT = T - T_ref,
  // on top of the muscle without it (the SLS's states follow x alone), whatever the signs: a
  // parallel spring of zero size could not soften (its floor), the slope and bend can.
  const std::vector<std::string> heated = {
      "drive.power={type: steps, initial: 0 W, times: [10 s], values: [1.5 W]}"};
  const Trace bare = simulate(physical_muscle_yaml(), heated);
  for (const auto& [beta, gamma] : {std::pair{-0.05, 0.0}, std::pair{0.02, -1e-3}}) {
    auto with = heated;
    with.push_back(
        "muscle.effects=[{type: thermal_softening, name: s, reference_stiffness: 0 N/m, "
        "temperature_coefficient: 0 1/K, reference_temperature: 20 degC, "
        "stiffness_slope: " +
        number(beta) + " N/(m*K), stiffness_curvature: " + number(gamma) + " N/(m*K^2)}]");
    const Trace sloped = simulate(physical_muscle_yaml(), with);
    INFO("beta = " << beta << ", gamma = " << gamma);
    REQUIRE(sloped.time.size() == bare.time.size());
    double largest = 0.0;
    for (std::size_t i = 0; i < bare.time.size(); ++i) {
      const double rise = bare["muscle/temperature"][i] - 293.15;
      const double expected = (beta + gamma * rise) * rise * bare["muscle/deflection"][i];
      const double added = sloped["muscle/force"][i] - bare["muscle/force"][i];
      CHECK(std::abs(added - expected) <= allowed(1e-8, 0.3));
      largest = std::max(largest, std::abs(expected));
    }
    CHECK(largest > 1e-3);  // the term is of millinewtons here, well above the tolerance
  }
}

TEST_CASE("A mass hangs still at the equilibrium that includes the attached terms' rest forces") {
  // m g = k1 x + phi_0 + F_n(x) + s(T_0) x at rest: a knee engaged below the balance and a
  // parallel spring at the starting (ambient) temperature move it from the SLS's own
  // (m g - phi_0) / k1 = 19.4 mm, and the muscle starts at rest there instead of settling.
  const std::string load =
      "load={type: hanging_mass, mass: 30 g, damping: 0.5 N*s/m, initial_deflection: equilibrium}";
  const std::string effects =
      "muscle.effects=[{type: nonlinear_stiffness, name: knee, stiffness: 5 N/m, "
      "knee_deflection: 15 mm, knee_width: 2 mm}, {type: thermal_softening, name: soft, "
      "reference_stiffness: 2 N/m, temperature_coefficient: -0.01 1/K, "
      "reference_temperature: 20 degC}]";
  const Trace plain = simulate(physical_muscle_yaml(), {load});
  const Trace held = simulate(physical_muscle_yaml(), {load, effects});
  const double weight = 0.03 * 9.80665;
  CHECK(plain["muscle/deflection"].front() == Approx((weight - 0.1) / 10.0).epsilon(1e-12));
  const double x0 = held["muscle/deflection"].front();
  CHECK(x0 < plain["muscle/deflection"].front() - 2e-3);  // the terms carry part of the weight
  const double knee = 5.0 * 2e-3 * std::log1p(std::exp((x0 - 15e-3) / 2e-3));
  CHECK(10.0 * x0 + 0.1 + knee + 2.0 * x0 == Approx(weight).epsilon(1e-12));
  double drift = 0.0;
  for (const double x : held["muscle/deflection"]) drift = std::max(drift, std::abs(x - x0));
  CHECK(drift < 1e-9);  // unheated, it stays where it started
}

TEST_CASE("Hysteresis given by its radius is a stop operator: force linear in its weight") {
  // dz/dt = k_h v - |v| z / r: on a rising branch z = k_h r - (k_h r - z0) exp(-dx / r), and
  // doubling k_h doubles z (the Prandtl-Ishlinskii operator is linear in its weights).
  auto run = [&](const std::string& stiffness) {
    auto overrides = triangle(40.0, 2);
    overrides.push_back("muscle.effects=[{type: hysteresis, name: play, stiffness: " + stiffness +
                        ", radius: 1.5 mm, follower_time: 1 ms}]");
    return simulate(physical_muscle_yaml(), overrides);
  };
  const Trace one = run("4 N/m"), two = run("8 N/m");
  const auto& z1 = one["muscle/play/force"];
  const auto& z2 = two["muscle/play/force"];
  double worst = 0.0, largest = 0.0;
  for (std::size_t i = 0; i < z1.size(); ++i) {
    worst = std::max(worst, std::abs(z2[i] - 2.0 * z1[i]));
    largest = std::max(largest, std::abs(z1[i]));
  }
  CHECK(largest == Approx(4.0 * 1.5e-3).epsilon(0.02));  // saturates at k_h r
  CHECK(worst <= allowed(1e-8, 4 * largest));            // z2's error and twice z1's
  // The same element given by F_h = k_h r is Dahl's, to the solver's tolerance.
  auto dahl = triangle(40.0, 2);
  dahl.push_back(
      "muscle.effects=[{type: hysteresis, name: play, stiffness: 4 N/m, force: 6 mN, "
      "follower_time: 1 ms}]");
  CHECK(max_abs_difference(simulate(physical_muscle_yaml(), dahl)["muscle/play/force"], z1) <=
        allowed(1e-8, largest));
}

TEST_CASE("Free convection with a free exponent loses G dT_ref (dT/dT_ref)^n") {
  FreeConvectionParameters p;
  p.conductance = 0.01;
  p.reference_difference = 50.0;
  p.exponent = 1.5;
  CHECK(FreeConvection::heat_loss(p, 50.0) == Approx(0.5).epsilon(1e-15));
  CHECK(FreeConvection::heat_loss(p, 25.0) == Approx(0.5 * std::pow(0.5, 1.5)).epsilon(1e-14));
  CHECK(FreeConvection::heat_loss(p, -25.0) == -FreeConvection::heat_loss(p, 25.0));
  p.exponent = 0.0;  // the laminar 5/4
  CHECK(FreeConvection::heat_loss(p, 25.0) == Approx(0.5 * std::pow(0.5, 1.25)).epsilon(1e-14));
  CHECK(config_error(physical_muscle_yaml(),
                     {"muscle.effects=[{type: free_convection, conductance: 0.01 W/K, "
                      "reference_difference: 50 K, exponent: 3}]"})
            .find("exponent") != std::string::npos);
}

TEST_CASE("A ratchet loses force by g times the heat above its threshold, and never regains it") {
  // dF_r/dt = -g max(0, T - T_th): under a power pulse F_r falls while T is above T_th and holds
  // when the muscle cools; it equals -g times the integral of the excess over the recorded T.
  const double rate = 2e-5, threshold = kAmbient + 20.0;
  const Trace trace = simulate(
      physical_muscle_yaml(),
      {"drive.power={type: steps, initial: 0 W, times: [10 s, 50 s], values: [1.5 W, 0 W]}",
       "scenario.duration=150 s", "output.rate=100 Hz",
       "muscle.effects=[{type: ratchet, name: creep, rate: 2e-5 N/(K*s), threshold: 40 degC}]"});
  const auto& t = trace.time;
  const auto& temperature = trace["muscle/temperature"];
  const auto& force = trace["muscle/creep/force"];
  double integral = 0.0, worst = 0.0;
  for (std::size_t i = 1; i < t.size(); ++i) {
    const double a = std::max(0.0, temperature[i - 1] - threshold);
    const double b = std::max(0.0, temperature[i] - threshold);
    integral += 0.5 * (a + b) * (t[i] - t[i - 1]);
    worst = std::max(worst, std::abs(force[i] + rate * integral));
    // Never regained, to the solver's tolerance (its interpolation between steps).
    CHECK(force[i] <= force[i - 1] + allowed(1e-8, std::abs(force[i])));
  }
  INFO("lost " << -force.back() << " N, worst error " << worst << " N");
  CHECK(-force.back() > 1e-3);
  // The trapezoid's error on the kinks where T crosses T_th, at 100 Hz, and the solver's.
  CHECK(worst <= 1e-3 * -force.back());
  // Cooled below the threshold: it holds.
  CHECK(std::abs(force.back() - force[t.size() - 200]) <= allowed(1e-8, -force.back()));
}

TEST_CASE("A heating-driven convection raises hA by G_P P / P_ref while the heater runs") {
  // The steady state of one node under power P: T - T_amb = P / (hA + G_P P / P_ref).
  const Trace trace =
      simulate(physical_muscle_yaml(),
               {kPowerStep, "scenario.duration=400 s",
                "muscle.effects=[{type: heating_convection, name: fan, conductance: 0.03 W/K, "
                "reference_power: 3 W}]"});
  CHECK(trace["muscle/temperature"].back() - kAmbient ==
        Approx(1.5 / (kConductance + 0.03 * 1.5 / 3.0)).epsilon(1e-6));
  // A boost that spins up with tau = 20 s reaches the same steady state, and while it spins up
  // it cools less than the boost that follows at once.
  const Trace lagged =
      simulate(physical_muscle_yaml(),
               {kPowerStep, "scenario.duration=400 s",
                "muscle.effects=[{type: heating_convection, name: fan, conductance: 0.03 W/K, "
                "reference_power: 3 W, time_constant: 20 s}]"});
  CHECK(lagged["muscle/temperature"].back() ==
        Approx(trace["muscle/temperature"].back()).epsilon(1e-6));
  const std::size_t spinning = 200;  // 20 s at 10 Hz: 10 s after the step
  CHECK(lagged["muscle/temperature"][spinning] > trace["muscle/temperature"][spinning] + 0.05);
}

namespace {
// The fan's switch, off at rest: s(P) = (sigma(P) - sigma(0)) / (1 - sigma(0)), sigma the
// logistic 1 / (1 + exp(-(P - P_on) / w)).
double fan_switch(double power, double on, double width) {
  const auto sigma = [&](double p) { return 1.0 / (1.0 + std::exp(-(p - on) / width)); };
  return (sigma(power) - sigma(0.0)) / (1.0 - sigma(0.0));
}
}  // namespace

TEST_CASE("A fan switched on above a power raises hA by G_P s(P), s a smooth switch at P_on") {
  // Steady states of one node under two powers, one below the switch and one above it:
  // T - T_amb = P / (hA + G_P s(P)).
  const double gain = 0.04, on = 1.6, width = 0.15;
  const Trace trace = simulate(
      physical_muscle_yaml(),
      {"drive.power={type: steps, initial: 0 W, times: [10 s, 400 s], values: [1 W, 2.5 W]}",
       "scenario.duration=800 s",
       "muscle.effects=[{type: heating_convection, name: fan, conductance: 0.04 W/K, "
       "switch_power: 1.6 W, switch_width: 0.15 W}]"});
  const auto steady = [&](double power) {
    return power / (kConductance + gain * fan_switch(power, on, width));
  };
  CHECK(trace["muscle/temperature"][3990] - kAmbient == Approx(steady(1.0)).epsilon(1e-6));
  CHECK(trace["muscle/temperature"].back() - kAmbient == Approx(steady(2.5)).epsilon(1e-6));
  // Below the switch the fan barely runs (s = 0.018): the rise is within 2 % of the bare node's
  // P/hA; above it nearly fully (s = 0.998): the node loses through hA + G_P.
  CHECK(trace["muscle/temperature"][3990] - kAmbient > 0.98 * 1.0 / kConductance);
  CHECK(trace["muscle/temperature"].back() - kAmbient < 2.5 / (kConductance + 0.99 * gain));
  CHECK_THAT(config_error(physical_muscle_yaml(),
                          {"muscle.effects=[{type: heating_convection, name: fan, conductance: "
                           "0.04 W/K, reference_power: 3 W, switch_power: 1.6 W, switch_width: "
                           "0.15 W}]"}),
             Catch::Contains("give reference_power (a boost proportional to the power) or "
                             "switch_power and switch_width"));
}

TEST_CASE("A switched fan is off at rest, however wide its switch") {
  // A switch so wide that the logistic alone would run at sigma(0) = 0.35 with the heater off.
  // After the heating stops the node cools through hA alone: T - T_amb = dT_0 exp(-hA t / C).
  const Trace trace = simulate(
      physical_muscle_yaml(),
      {"drive.power={type: steps, initial: 0 W, times: [10 s, 300 s], values: [2.5 W, 0 W]}",
       "scenario.duration=400 s",
       "muscle.effects=[{type: heating_convection, name: fan, conductance: 0.04 W/K, "
       "switch_power: 0.3 W, switch_width: 0.5 W}]"});
  CHECK(fan_switch(0.0, 0.3, 0.5) == 0.0);
  CHECK(fan_switch(1e3, 0.3, 0.5) == Approx(1.0).epsilon(1e-12));
  const std::size_t off = 3000, later = 3500;  // 300 s and 350 s at 10 Hz
  REQUIRE(trace.time[off] == Approx(300.0));
  const double rise_off = trace["muscle/temperature"][off] - kAmbient;
  const double rise_later = trace["muscle/temperature"][later] - kAmbient;
  // Within the solver's tolerance on a 50 K rise, as the sibling tests bound it; the logistic
  // alone would have cooled it to 0.06 K, not 0.19 K.
  CHECK(std::abs(rise_later - rise_off * std::exp(-kConductance / kCapacity * 50.0)) <=
        allowed(1e-8, 50.0) + 50.0 * 1e-6);
  // Before the heating starts it takes nothing either: the node stays at ambient.
  CHECK(trace["muscle/temperature"][50] == Approx(kAmbient).epsilon(1e-12));
}

TEST_CASE("A switched fan driven through a lag follows the switch of the lagged power") {
  // Power step P at t_s = 10 s into one node with a fan switched at P_on through the lag tau:
  //   C dT/dt = P - hA (T - T_amb) - G_P s(P_b) (T - T_amb),   tau dP_b/dt = P - P_b,
  // P_b = 0 at the start. The reference is the classical Runge-Kutta method with 1 ms steps,
  // whose error (of order dt^4) is far below the solver's.
  const double gain = 0.04, on = 1.6, width = 0.15, tau = 20.0, power = 2.5, step = 10.0;
  const auto switched = [&](double lagged) { return fan_switch(lagged, on, width); };
  const auto slope = [&](const Eigen::Vector2d& y) {  // y = (T - T_amb, P_b) after the step
    return Eigen::Vector2d((power - (kConductance + gain * switched(y(1))) * y(0)) / kCapacity,
                           (power - y(1)) / tau);
  };
  const Trace trace =
      simulate(physical_muscle_yaml(),
               {"drive.power={type: steps, initial: 0 W, times: [10 s], values: [2.5 W]}",
                "scenario.duration=200 s",
                "muscle.effects=[{type: heating_convection, name: fan, conductance: 0.04 W/K, "
                "switch_power: 1.6 W, switch_width: 0.15 W, time_constant: 20 s}]"});
  Eigen::Vector2d y(0.0, 0.0);
  double t = step, worst = 0.0;
  constexpr double dt = 1e-3;
  for (std::size_t i = 0; i < trace.time.size(); ++i) {
    if (trace.time[i] <= step) continue;
    while (t < trace.time[i] - dt / 2) {
      const Eigen::Vector2d k1 = slope(y), k2 = slope(y + dt / 2 * k1), k3 = slope(y + dt / 2 * k2),
                            k4 = slope(y + dt * k3);
      y += dt / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
      t += dt;
    }
    worst = std::max(worst, std::abs(trace["muscle/temperature"][i] - kAmbient - y(0)));
  }
  INFO("worst error " << worst << " K");
  CHECK(worst <= allowed(1e-8, 50.0) + 50.0 * 1e-6);
  // The fan comes on only once the lagged power passes P_on, tau ln(P / (P - P_on)) = 20.4 s
  // after the step: until then the node heats nearly as the bare one, C dT/dt = P - hA dT.
  const double bare = power / kConductance * (1.0 - std::exp(-kConductance / kCapacity * 10.0));
  CHECK(trace["muscle/temperature"][200] - kAmbient == Approx(bare).epsilon(0.01));
  CHECK(trace["muscle/temperature"].back() - kAmbient ==
        Approx(power / (kConductance + gain * switched(power))).epsilon(2e-3));
}
