// Antagonistic pairs: two muscles on a pulley joint, against the joint's static balance and
// stiffness worked out by hand, and the joint-angle controller's law.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "controllers/joint_angle_controller.h"
#include "models/antagonistic_joint.h"
#include "models/muscle.h"
#include "tests/support/test_support.h"

using namespace tcpmsim;
using namespace tcpmsim::testing;

namespace {

// Table 7.2's muscle (SI), reduced thermal form.
constexpr double k1 = 10.8, k2 = 2.7, phi0 = 0.1069;
constexpr double kappa_p = 7.2e-3, kappa_c = 0.1316, phi_t = 4.0e-3;
constexpr double radius = 0.01;

// Two Table 7.2 muscles (with `effects` appended to each) on a joint, each heated at its own
// constant power from the start with F_T already at its steady state kappa_P P / kappa_c, so
// that the pair starts at rest (at its static balance with initial_angle: equilibrium in
// `joint_extra`); a load torque step of `torque` at 20 s.
std::string pair_at_rest(double left_power, double right_power, const std::string& joint_extra,
                         double torque, const std::string& effects = "",
                         double force_offset = phi0) {
  const auto muscle = [&](double power) {
    return "    thermal_force: {form: reduced, kappa_P: 7.2e-3 N/J, kappa_c: 0.1316 1/s, "
           "ambient_temperature: 23 degC, force_per_kelvin: 4.0e-3 N/K, initial_thermal_force: " +
           number(kappa_p * power / kappa_c) +
           " N}\n    mechanics: {k1: 10.8 N/m, k2: 2.7 N/m, damping: 4.3 N*s/m, force_offset: " +
           number(force_offset) +
           " N}\n    resistance: 10.18 ohm\n    inductance: {quantity: measure, lambda_l: 2.81 mm, "
           "lambda_x: 28.8 mm, lambda_0: 0.433}\n" +
           effects;
  };
  return R"(scenario: {name: pair, duration: 200 s}
output: {rate: 1 Hz}
solver: {rtol: 1.0e-10}
muscles:
  left:
)" + muscle(left_power) +
         "  right:\n" + muscle(right_power) +
         "drives:\n  d1: {muscle: left, mode: power, power: " + number(left_power) +
         " W}\n  d2: {muscle: right, mode: power, power: " + number(right_power) + R"( W}
load:
  type: joint
  left: left
  right: right
  radius: 10 mm
  inertia: 1.0e-5 kg*m^2
  damping: 1.0e-4 N*m*s/rad
  load_torque: {type: steps, initial: 0 N*m, times: [20 s], values: [)" +
         number(torque) + " N*m]}\n" + joint_extra;
}

// The angle's change under the torque step, once everything has relaxed (at 200 s), and the
// static stiffness the step measures.
double measured_stiffness(const Trace& trace, double torque) {
  const auto& angle = trace["load/angle"];
  return torque / (angle.back() - angle[19]);
}

}  // namespace

TEST_CASE("A pair's static joint stiffness is r^2 (k_left + k_right) + k_s at any pretension") {
  const double torque = 2.0e-5;  // N m: 0.01 rad against 2.2e-3 N m/rad, both stay taut
  const double spring = 1.0e-4;  // N m/rad
  const double expected = radius * radius * (k1 + k1) + spring;
  const std::string joint =
      "  pre_deflection: {left: 20 mm, right: 12 mm}\n  initial_angle: equilibrium\n"
      "  spring: {stiffness: 1.0e-4 N*m/rad, rest_angle: 0.05 rad}\n";
  // Co-contraction from barely heated to well heated, and unequal heating: the pretension
  // changes by a factor of about two, the stiffness of linear muscles not at all.
  for (const auto& [left, right] :
       std::vector<std::pair<double, double>>{{0.0, 0.0}, {0.3, 0.3}, {2.5, 2.5}, {0.5, 2.0}}) {
    INFO("powers " << left << " W, " << right << " W");
    const Trace trace = simulate(pair_at_rest(left, right, joint, torque));
    CHECK(trace["left/force"][19] > 0.1);  // taut
    CHECK(trace["right/force"][19] > 0.1);
    // The start is the static balance (7.5) with relaxed dashpots, solved by hand: r (F_R -
    // F_L) - k_s (theta - theta_s) = 0 with F = k1 x + F_T + phi_0 is linear in theta.
    const double ft_left = kappa_p * left / kappa_c, ft_right = kappa_p * right / kappa_c;
    const double balance =
        (radius * (k1 * 0.012 + ft_right - k1 * 0.020 - ft_left) + spring * 0.05) / expected;
    CHECK(trace["load/angle"][0] == Approx(balance).epsilon(1e-12));
    CHECK(trace["load/angle"][19] == Approx(balance).epsilon(1e-7));
    CHECK(measured_stiffness(trace, torque) == Approx(expected).epsilon(1e-6));
    CHECK(trace["load/stiffness"].back() == Approx(expected).epsilon(1e-14));
    // Before it relaxes the pair meets a torque step with k1 + k2 each.
    CHECK(trace["load/instantaneous_stiffness"].back() ==
          Approx(radius * radius * 2.0 * (k1 + k2) + spring).epsilon(1e-14));
  }
}

TEST_CASE("With muscles that soften when hot, co-contraction lowers the joint's stiffness") {
  // s(T) = s_ref (1 + alpha (T - T_ref)) in parallel with each SLS; T = T_amb + F_T / phi_T.
  const double s_ref = 8.0, alpha = -0.01;
  const std::string softening =
      "    effects: [{type: thermal_softening, name: softening, reference_stiffness: 8 N/m, "
      "temperature_coefficient: -0.01 1/K, reference_temperature: 23 degC}]\n";
  const std::string joint =
      "  pre_deflection: {left: 20 mm, right: 20 mm}\n  initial_angle: 0 rad\n";
  double previous = std::numeric_limits<double>::infinity();  // the measured stiffness
  for (const double power : {0.0, 1.0, 2.5}) {
    INFO("co-contraction " << power << " W each");
    const Trace trace = simulate(pair_at_rest(power, power, joint, 2.0e-5, softening));
    const double heating = kappa_p * power / kappa_c / phi_t;  // T - T_amb [K]
    const double s = s_ref * (1.0 + alpha * heating);
    const double expected = radius * radius * 2.0 * (k1 + s);
    const double measured = measured_stiffness(trace, 2.0e-5);
    CHECK(measured == Approx(expected).epsilon(1e-6));
    CHECK(trace["load/stiffness"].back() == Approx(expected).epsilon(1e-9));
    CHECK(trace["left/softening/stiffness"].back() == Approx(s).epsilon(1e-9));
    CHECK(measured < previous);  // hotter: softer, as the torque step measures it
    previous = measured;
  }
}

TEST_CASE("A muscle the joint would compress goes slack instead: no compression, its own length") {
  // With a negative offset (both muscles) the right muscle would push at its 0 mm
  // pre-deflection if held there; the spring holds the joint against the left muscle alone.
  const double offset = -0.2, spring = 1.0e-3;
  const std::string joint =
      "  pre_deflection: {left: 20 mm, right: 0 mm}\n  initial_angle: equilibrium\n"
      "  spring: {stiffness: 1.0e-3 N*m/rad}\n";
  const Trace trace = simulate(pair_at_rest(0.0, 0.0, joint, 1.0e-5, "", offset));
  const auto& force = trace["right/force"];
  for (std::size_t k = 0; k < force.size(); ++k) {
    REQUIRE(force[k] == 0.0);  // slack, never negative
    // The muscle sits at its force-free deflection, longer than the cable's path.
    REQUIRE(trace["right/deflection"][k] > trace["load/right_deflection"][k]);
  }
  // At rest its free deflection is -phi_0 / k1 (F_T = 0).
  CHECK(trace["right/deflection"].back() == Approx(-offset / k1).epsilon(1e-9));
  // The joint balances the left muscle against the spring alone:
  //   -r (k1 (x0 + r theta) + phi_0) - k_s theta = 0.
  const double alone = -radius * (k1 * 0.020 + offset) / (spring + radius * radius * k1);
  CHECK(trace["load/angle"][0] == Approx(alone).epsilon(1e-12));
  // The slack muscle adds nothing to the stiffness.
  CHECK(trace["load/stiffness"].back() == Approx(radius * radius * k1 + spring).epsilon(1e-12));
  CHECK(measured_stiffness(trace, 1.0e-5) == Approx(radius * radius * k1 + spring).epsilon(1e-6));
}

TEST_CASE(
    "The joint-angle law: push-pull around the co-contraction, the angle from two "
    "deflections") {
  using namespace joint_angle;
  // Within the limits the pair's difference is u and its mean the co-contraction.
  const auto inside = push_pull(1.6, 0.8, 0.1, 3.12);
  CHECK(inside.right - inside.left == Approx(0.8).epsilon(1e-15));
  CHECK(0.5 * (inside.right + inside.left) == Approx(1.6).epsilon(1e-15));
  // Past one limit only the other side moves; at differential_limit both are clamped.
  const auto beyond = push_pull(2.0, 3.0, 0.1, 3.12);
  CHECK(beyond.right == 3.12);
  CHECK(beyond.left == Approx(0.5).epsilon(1e-15));
  const double bound = differential_limit(2.0, 0.1, 3.12);
  CHECK(bound == Approx(3.8).epsilon(1e-15));
  const auto clamped = push_pull(2.0, bound, 0.1, 3.12);
  CHECK(clamped.left == Approx(0.1).epsilon(1e-15));
  CHECK(clamped.right == 3.12);
  // The cable geometry inverted: deflections at angle theta give theta back, and a common
  // shift of both (a shared error) cancels.
  const JointGeometry geometry{0.01, 0.020, 0.012};
  const double theta = 0.37;
  const double left = joint::left_deflection(geometry, theta);
  const double right = joint::right_deflection(geometry, theta);
  CHECK(left == Approx(0.020 + 0.01 * theta).epsilon(1e-15));  // x0 + r theta, by hand
  CHECK(right == Approx(0.012 - 0.01 * theta).epsilon(1e-15));
  CHECK(joint::angle_from_deflections(geometry, left, right) == Approx(theta).epsilon(1e-14));
  CHECK(joint::angle_from_deflections(geometry, left + 1e-3, right + 1e-3) ==
        Approx(theta).epsilon(1e-13));
}

TEST_CASE("Joint-angle control through the encoder holds the reference, at any co-contraction") {
  Scenario scenario =
      load_scenario(source_path("configs/pair/pretension_change.yaml"), {}, shared_units());
  const Trace trace = simulate(scenario);
  const auto& time = trace.time;
  const auto& angle = trace["load/angle"];
  const auto& reference = trace["controller/reference"];
  const auto& co = trace["controller/co_contraction"];
  const auto& left_power = trace["controller/left_power_command"];
  const auto& right_power = trace["controller/right_power_command"];
  // Settled before and after the co-contraction change: within the encoder's resolution, and
  // the powers push and pull around the level (1.2 W, then 2.4 W) inside their limits.
  for (std::size_t k = 0; k < time.size(); ++k) {
    const bool settled = (time[k] > 50.0 && time[k] < 60.0) || time[k] > 170.0;
    if (settled) {
      INFO("t = " << time[k]);
      REQUIRE(std::abs(angle[k] - reference[k]) < 2e-3);
      REQUIRE(0.5 * (left_power[k] + right_power[k]) == Approx(time[k] < 60.0 ? 1.2 : 2.4));
      REQUIRE(co[k] == (time[k] < 60.0 ? 1.2 : 2.4));
      REQUIRE(left_power[k] > 0.1);
      REQUIRE(right_power[k] < 3.12);
    }
  }
  // Both taut throughout.
  for (const char* muscle : {"left/force", "right/force"})
    for (double f : trace[muscle]) REQUIRE(f > 0.0);
  // The stiffness from each muscle's recorded temperature through the softening law written out
  // here, s = 3 N/m (1 - 0.02/K (T - 296.15 K)): r^2 (2 k1 + s_left + s_right).
  const auto by_hand = [&](std::size_t k) {
    const auto s = [](double t) { return 3.0 * (1.0 - 0.02 * (t - 296.15)); };
    return radius * radius *
           (2.0 * k1 + s(trace["left/temperature"][k]) + s(trace["right/temperature"][k]));
  };
  const std::size_t before = 590, after = time.size() - 1;  // 59 s and 200 s
  CHECK(trace["load/stiffness"][before] == Approx(by_hand(before)).epsilon(1e-12));
  CHECK(trace["load/stiffness"][after] == Approx(by_hand(after)).epsilon(1e-12));
  // What the README states, and a fall of 8 % for twice the co-contraction.
  CHECK(trace["load/stiffness"][before] == Approx(2.563e-3).epsilon(1e-3));
  CHECK(trace["load/stiffness"][after] == Approx(2.366e-3).epsilon(1e-3));
}

TEST_CASE("Joint-angle control through self-sensing reaches every step it is given") {
  // The controller sees only the two estimators' deflections (each from its Muscle Drive's L*).
  // Uncalibrated, the estimated angle is off by up to about 0.08 rad at the end of a hold; the
  // steps are 0.13 to 0.8 rad. A wrong sign or swapped estimators would run to a power limit.
  Scenario scenario =
      load_scenario(source_path("configs/pair/angle_steps.yaml"), {}, shared_units());
  const Trace trace = simulate(scenario);
  const auto& time = trace.time;
  const auto& angle = trace["load/angle"];
  const auto& estimate = trace["controller/angle"];
  const auto& reference = trace["controller/reference"];
  for (double end = 59.95; end < 180.0; end += 20.0) {
    const auto k =
        static_cast<std::size_t>(std::min_element(time.begin(), time.end(),
                                                  [end](double a, double b) {
                                                    return std::abs(a - end) < std::abs(b - end);
                                                  }) -
                                 time.begin());
    INFO("end of the hold at " << time[k] << " s, reference " << reference[k] << " rad");
    CHECK(std::abs(angle[k] - reference[k]) < 0.08);
    CHECK(std::abs(estimate[k] - angle[k]) < 0.09);
  }
}

TEST_CASE("Each muscle under its own force control: the joint's spring takes the difference") {
  Scenario scenario =
      load_scenario(source_path("configs/pair/independent_force.yaml"), {}, shared_units());
  const Trace trace = simulate(scenario);
  // At rest the torque balance is r (F_right - F_left) = k_s theta (no load torque).
  const double radius_m = 0.01, spring = 2.0e-3;
  const auto& angle = trace["load/angle"];
  const double balance =
      radius_m * (trace["right/force"].back() - trace["left/force"].back()) / spring;
  CHECK(std::abs(angle.back()) > 0.05);  // the tensions do differ
  CHECK(angle.back() == Approx(balance).epsilon(0.02));
}

TEST_CASE("A joint and its controller refuse what they cannot build, with a located message") {
  const std::string pair =
      pair_at_rest(0.5, 0.5, "  pre_deflection: {left: 20 mm, right: 20 mm}\n", 0.0);
  CHECK_THAT(config_error(replaced(pair, "  right: right\n  radius", "  right: left\n  radius")),
             Catch::Contains("load.right: expected a muscle other than the left one"));
  CHECK_THAT(config_error(pair + "  initial_angle: equilibrium\n",
                          {"muscles.left.effects=[{type: thermal_softening, reference_stiffness: "
                           "1 N/m, temperature_coefficient: -0.01 1/K, reference_temperature: "
                           "300 K}]"}),
             Catch::Contains("left has an effect that carries force at rest; give the angle"));
  // A joint-angle controller needs Muscle Drives that take its commands.
  CHECK_THAT(config_error(pair + "controller: {type: joint_angle, feedback: encoder, reference: "
                                 "0 rad, co_contraction: 1 W, gains: {proportional: 20 W/rad, "
                                 "integral_time: 2 s}, power_limits: [0.1 W, 3 W]}\n"),
             Catch::Contains("controller: joint-angle control commands the Muscle Drive"));
  // Two PWM frequencies for one controller: reported at the setting that differs (issue 31).
  CHECK_THAT(config_error(read_text_file(source_path("configs/pair/angle_steps.yaml")),
                          {"drives.right_drive.pwm_frequency=40 Hz"}),
             Catch::StartsWith("command line (--set drives.right_drive.pwm_frequency=40 Hz): "
                               "error: drives.right_drive.pwm_frequency: the drives left_drive "
                               "and right_drive run at different PWM frequencies"));
}

TEST_CASE("A muscle that goes slack under a torque step carries nothing and leaves the stiffness") {
  // Taut at the start (15 mm each, phi_0 = -0.1 N: F = 62 mN); a torque of 2e-3 N m turns the
  // joint past the point where the right muscle's cable would have to push (x_right < -phi_0/k1
  // = 9.26 mm), and it goes slack. The left muscle alone then balances the torque:
  //   -r (k1 (x0 + r theta) + phi_0) + tau = 0.
  const double offset = -0.1, torque = 2.0e-3;
  const std::string joint =
      "  pre_deflection: {left: 15 mm, right: 15 mm}\n  initial_angle: equilibrium\n";
  const Trace trace = simulate(pair_at_rest(0.0, 0.0, joint, torque, "", offset));
  const auto& force = trace["right/force"];
  CHECK(force[19] == Approx(k1 * 0.015 + offset).epsilon(1e-9));  // taut before the step
  for (double f : force) REQUIRE(f >= 0.0);
  CHECK(force.back() == 0.0);
  CHECK(trace["right/deflection"].back() == Approx(-offset / k1).epsilon(1e-9));
  const double alone = (torque / radius - (k1 * 0.015 + offset)) / (radius * k1);
  CHECK(trace["load/angle"].back() == Approx(alone).epsilon(1e-7));
  CHECK(trace["load/stiffness"][19] == Approx(radius * radius * 2.0 * k1).epsilon(1e-12));
  CHECK(trace["load/stiffness"].back() == Approx(radius * radius * k1).epsilon(1e-12));
}

TEST_CASE("The discrete PID saturates and bleeds its integral against per-sample limits") {
  PidSettings settings;
  settings.gains = {1.0, 1.0, 0.0};  // K_p = 1, T_i = 1 s
  settings.power_min = -10.0;
  settings.power_max = 10.0;
  DiscretePid law(settings, 1.0);
  // e = 2, limits [-0.5, 0.5]: P_d = 2, P = 0.5, z = e - (P_d - P) / K_p = 0.5, I = 0.5 (7.8).
  auto step = law.update(2.0, 0.0, 0.0, -0.5, 0.5);
  CHECK(step.demand == 2.0);
  CHECK(step.command == 0.5);
  CHECK(law.integral() == 0.5);
  // Wider limits at the next sample: P_d = K_p (e + I / T_i) = 2.5, unsaturated, I = 2.5.
  step = law.update(2.0, 0.0, 0.0, -3.0, 3.0);
  CHECK(step.demand == 2.5);
  CHECK(step.command == 2.5);
  CHECK(law.integral() == 2.5);
  // Without anti-windup the integral takes the whole error under saturation.
  settings.anti_windup = false;
  DiscretePid plain(settings, 1.0);
  plain.update(2.0, 0.0, 0.0, -0.5, 0.5);
  CHECK(plain.integral() == 2.0);
}

TEST_CASE("A hanging mass at equilibrium takes a muscle's force at rest into its balance") {
  // The pair's joint refuses such a muscle (above); a hanging mass balances it (the balance of
  // the attached terms is specified in test_effects.cpp).
  std::string yaml = example_muscle_scenario(
      "  effects: [{type: thermal_softening, reference_stiffness: 1 N/m, "
      "temperature_coefficient: -0.01 1/K, reference_temperature: 296.15 K}]\n",
      "drive: {mode: power, power: 1 W}\nload: {type: hanging_mass, mass: 35 g, "
      "initial_deflection: equilibrium}\n");
  CHECK(config_error(yaml) == "no error");
}
