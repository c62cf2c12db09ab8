// The effect terms the discovery workflow attaches (thermal_lag, hysteresis,
// nonlinear_stiffness), each against its analytic solution.
#include <catch2/catch.hpp>

#include <Eigen/Dense>

#include <cmath>

#include "tests/support/test_support.h"

using namespace tcpmsim;
using namespace tcpmsim::testing;

namespace {

constexpr double kAmbient = 293.15, kCapacity = 0.5, kConductance = 0.05;  // the test muscle
constexpr double kWireCapacity = 0.05, kWireConductance = 0.02;            // J/K, W/K

// The two-node network after a power step P at t_s, both nodes at ambient before it:
//   C dT/dt = G_w (T_w - T) - hA (T - T_amb),   C_w dT_w/dt = P - G_w (T_w - T),
// solved through the eigenvectors of its (real, distinct) eigenvalues.
double two_node_temperature(double t, double step_time, double power) {
  if (t <= step_time) return kAmbient;
  Eigen::Matrix2d a;
  a << -(kWireConductance + kConductance) / kCapacity, kWireConductance / kCapacity,
      kWireConductance / kWireCapacity, -kWireConductance / kWireCapacity;
  const Eigen::Vector2d forcing(0.0, power / kWireCapacity);
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
