// Composition: several named instances in one scenario, links between them by name, and
// effects attached to a muscle from the scenario, each against an analytic solution.
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <sstream>
#include <unsupported/Eigen/MatrixFunctions>

#include "models/effects/free_convection.h"
#include "tests/support/test_support.h"

using namespace tcpmsim;
using namespace tcpmsim::testing;

namespace {

// Table 7.2's muscle, no power (F_T stays 0), with `extra` appended to its section.
std::string passive_muscle(const std::string& extra, const std::string& load) {
  return R"(scenario: {name: test, duration: 40 s}
output: {rate: 20 Hz}
solver: {rtol: 1.0e-10}
muscle:
  thermal_force: {form: reduced, kappa_P: 7.2e-3 N/J, kappa_c: 131.6e-3 1/s, ambient_temperature: 23 degC}
  mechanics: {k1: 10.8 N/m, k2: 2.7 N/m, damping: 4.3 N*s/m, force_offset: 0.1069 N}
  resistance: 10.18 ohm
  inductance: {quantity: measure, lambda_l: 2.81 mm, lambda_x: 28.8 mm, lambda_0: 0.433}
)" + extra +
         "drive: {mode: power, power: 0 W}\n" + load;
}

constexpr double k1 = 10.8, k2 = 2.7, c = 4.3, phi0 = 0.1069;  // the muscle above, SI
constexpr double kb = 5.0, cb = 50.0;  // the attached branch: tau = 10 s against the SLS's 1.6 s
const std::string kBranch =
    "  effects: [{type: maxwell_branch, name: slow, stiffness: 5 N/m, damping: 50 N*s/m}]\n";

}  // namespace

TEST_CASE("Two muscles on one imposed deflection: each records under its name, the forces sum") {
  Scenario pair = load_scenario(source_path("configs/composition/two_muscles.yaml"),
                                {"solver.rtol=1e-9"}, shared_units());
  const Trace both = simulate(pair);
  const auto& m1 = both["m1/force"];
  const auto& m2 = both["m2/force"];
  const auto& cell = both["load/force"];
  REQUIRE(m1.size() == 1201);
  for (std::size_t k = 0; k < m1.size(); ++k) REQUIRE(cell[k] == m1[k] + m2[k]);  // bit for bit
  CHECK(both["m1/deflection"] == both["m2/deflection"]);  // one imposed deflection
  CHECK(max_abs_difference(m1, m2) > 0.05);               // two drives, two different muscles

  // Side by side on an imposed deflection the muscles do not interact: m1 behaves as it does
  // alone, with its own drive, to the integration error.
  std::string alone = R"(scenario: {name: alone, duration: 120 s, seed: 11}
output: {rate: 10 Hz}
solver: {rtol: 1.0e-9}
muscle:
  thermal_force: {form: reduced, kappa_P: 7.2e-3 N/J, kappa_c: 131.6e-3 1/s, ambient_temperature: 23 degC, force_per_kelvin: 4.0e-3 N/K}
  mechanics: {k1: 10.8e-3 N/mm, k2: 2.7e-3 N/mm, damping: 4.3e-3 N*s/mm, force_offset: 106.9e-3 N}
  resistance: 10.18 ohm
  inductance: {quantity: measure, lambda_l: 2.81 mm, lambda_x: 28.8 mm, lambda_0: 0.433}
drive: {mode: power, power: {type: steps, initial: 0.5 W, times: [20 s, 60 s], values: [2.5 W, 1 W]}}
load: {type: deflection, deflection: {type: staircase, levels: [20 mm, 25 mm, 15 mm], hold: 30 s, rate: 1 mm/s}}
)";
  const Trace single = simulate(alone);
  CHECK(max_abs_difference(single["muscle/force"], m1) < allowed(1e-9, 0.6));
  CHECK(single["muscle/temperature"].back() == Approx(both["m1/temperature"].back()));
}

TEST_CASE("A parameter of a named instance is set by its instance path, with units") {
  const std::string file = source_path("configs/composition/two_muscles.yaml");
  const Trace by_name = simulate(load_scenario(file, {"m2.mechanics.k2=3 mN/mm"}, shared_units()));
  const Trace by_section =
      simulate(load_scenario(file, {"muscles.m2.mechanics.k2=3 N/m"}, shared_units()));
  const Trace unchanged = simulate(load_scenario(file, {}, shared_units()));
  CHECK(by_name["m2/force"] == by_section["m2/force"]);
  // m1 shares only the solver's steps with m2: it moves within the integration error.
  CHECK(max_abs_difference(by_name["m1/force"], unchanged["m1/force"]) < allowed(1e-6, 0.6));
  CHECK(max_abs_difference(by_name["m2/force"], unchanged["m2/force"]) > 1e-3);
}

TEST_CASE("Links between instances are explicit, with the only candidate as default") {
  std::string text;
  {
    std::ifstream file(source_path("configs/composition/two_muscles.yaml"));
    std::stringstream buffer;
    buffer << file.rdbuf();
    text = buffer.str();
  }
  CHECK(config_error(text) == "no error");
  CHECK_THAT(config_error(replaced(text, "  muscles: [m1, m2]\n", "")),
             Catch::Contains("load: the scenario has several muscles; say which with 'muscle: "
                             "<name>'"));
  CHECK_THAT(config_error(replaced(text, "muscle: m2", "muscle: m3")),
             Catch::Contains("drives.d2.muscle: no muscle named 'm3' (did you mean 'm1'?); the "
                             "scenario's: m1, m2"));
  CHECK_THAT(config_error(replaced(text, "  d2:", "  m1:")),
             Catch::Contains("two instances are named 'm1'; names must be unique"));
  CHECK_THAT(config_error(replaced(text, "  m2:\n", "  m.2:\n")),
             Catch::Contains("expected an instance name without dots"));
}

TEST_CASE("An attached Maxwell branch relaxes with its own time constant beside the SLS's") {
  // Deflection step dx at t = 1 s from rest: F - phi_0 - k1 x = dx (k2 e^(-t k2/c) +
  // kb e^(-t kb/cb)), the generalized Maxwell solid's two relaxation times (1.59 s and 10 s).
  const Trace trace = simulate(passive_muscle(
      kBranch,
      "load: {type: deflection, deflection: {type: steps, initial: 20 mm, times: [1 s], "
      "values: [25 mm]}}\n"));
  const double x0 = 20e-3, x1 = 25e-3, dx = x1 - x0;
  double worst = 0.0, worst_branch = 0.0;
  for (std::size_t k = 0; k < trace.time.size(); ++k) {
    const double t = trace.time[k] - 1.0;
    const double expected =
        t < 0 ? k1 * x0 + phi0
              : k1 * x1 + phi0 + dx * (k2 * std::exp(-t * k2 / c) + kb * std::exp(-t * kb / cb));
    const double branch = t < 0 ? 0.0 : kb * dx * std::exp(-t * kb / cb);
    worst = std::max(worst, std::abs(trace["muscle/force"][k] - expected));
    worst_branch = std::max(worst_branch, std::abs(trace["muscle/slow/force"][k] - branch));
  }
  INFO("worst force error " << worst << " N, branch " << worst_branch << " N");
  CHECK(worst < allowed(1e-10, 0.5));
  CHECK(worst_branch < allowed(1e-10, 0.5));
  // Without the branch the slow tail is absent: the same formula misses by kb dx e^(-t/10 s).
  const Trace bare = simulate(passive_muscle(
      "",
      "load: {type: deflection, deflection: {type: steps, initial: 20 mm, times: [1 s], "
      "values: [25 mm]}}\n"));
  CHECK(max_abs_difference(bare["muscle/force"], trace["muscle/force"]) > 0.5 * kb * dx);
}

TEST_CASE("A Maxwell branch given by its time constant relaxes as c_b = k_b tau_b") {
  // The same step as above with tau_b = 10 s instead of c_b = 50 N s/m: the analytic relaxation
  // kb dx e^(-t / tau_b), and the run of the damping form to the solver's tolerance.
  const std::string step =
      "load: {type: deflection, deflection: {type: steps, initial: 20 mm, times: [1 s], "
      "values: [25 mm]}}\n";
  const Trace by_time = simulate(passive_muscle(
      "  effects: [{type: maxwell_branch, name: slow, stiffness: 5 N/m, time_constant: 10 s}]\n",
      step));
  const double dx = 5e-3;
  double worst = 0.0;
  for (std::size_t k = 0; k < by_time.time.size(); ++k) {
    const double t = by_time.time[k] - 1.0;
    const double branch = t < 0 ? 0.0 : kb * dx * std::exp(-t / (cb / kb));
    worst = std::max(worst, std::abs(by_time["muscle/slow/force"][k] - branch));
  }
  CHECK(worst < allowed(1e-10, 0.5));
  CHECK(max_abs_difference(by_time["muscle/force"],
                           simulate(passive_muscle(kBranch, step))["muscle/force"]) <
        allowed(1e-10, 0.5));
  CHECK_THAT(config_error(passive_muscle("  effects: [{type: maxwell_branch, stiffness: 5 N/m, "
                                         "damping: 50 N*s/m, time_constant: 10 s}]\n",
                                         step)),
             Catch::Contains("give damping or time_constant"));
}

TEST_CASE("Under an imposed force the attached branch adds its creep time to the SLS's") {
  // Force step F0 -> F1 at t = 1 s from rest. States z = (x_d, y) with
  // x = (F - phi_0 + k2 x_d + kb y) / K, K = k1 + k2 + kb: dz/dt = A z + b, so
  // z(t) = z_inf + exp(A t) (z0 - z_inf) with both dashpots at rest at x_inf = (F1 - phi_0)/k1.
  const double f0 = 0.35, f1 = 0.45;
  const Trace trace = simulate(
      passive_muscle(kBranch,
                     "load: {type: force, force: {type: steps, initial: 0.35 N, times: [1 s], "
                     "values: [0.45 N]}}\n"));
  const double total = k1 + k2 + kb;
  Eigen::Matrix2d a;
  a << k2 / c * (k2 / total - 1.0), k2 / c * kb / total, kb / cb * k2 / total,
      kb / cb * (kb / total - 1.0);
  const double x0 = (f0 - phi0) / k1, x_inf = (f1 - phi0) / k1;
  const Eigen::Vector2d start(x0 - x_inf, x0 - x_inf);
  double worst = 0.0;
  for (std::size_t k = 0; k < trace.time.size(); ++k) {
    const double t = trace.time[k] - 1.0;
    double expected = x0;
    if (t >= 0) {
      const Eigen::Vector2d z = Eigen::Vector2d::Constant(x_inf) + (a * t).exp() * start;
      expected = (f1 - phi0 + k2 * z(0) + kb * z(1)) / total;
    }
    worst = std::max(worst, std::abs(trace["muscle/deflection"][k] - expected));
  }
  INFO("worst deflection error " << worst << " m");
  CHECK(worst < allowed(1e-10, 0.05));
  // Without the branch the step is larger (0.1 N / 13.5 N/m against 0.1 N / 18.5 N/m at once).
  const Trace bare = simulate(
      passive_muscle("",
                     "load: {type: force, force: {type: steps, initial: 0.35 N, times: [1 s], "
                     "values: [0.45 N]}}\n"));
  CHECK(max_abs_difference(bare["muscle/deflection"], trace["muscle/deflection"]) > 1e-3);
}

TEST_CASE("Free convection attached to the heat balance sets the steady temperature it predicts") {
  // P = hA dT + G dT_ref (dT/dT_ref)^(5/4) at steady state; energy stays balanced throughout.
  // 1.5 W with hA = G = 0.01 W/K at dT_ref = 50 K.
  const std::string yaml = R"(scenario: {name: test, duration: 400 s}
output: {rate: 1 Hz}
solver: {rtol: 1.0e-10}
muscle:
  thermal: {heat_capacity: 0.3 J/K, conductance: 0.01 W/K, ambient_temperature: 23 degC, energy_accounting: true}
  thermal_force: {form: physical, force_per_kelvin: 0.004 N/K, reference_temperature: 23 degC}
  mechanics: {k1: 10.8 N/m, k2: 2.7 N/m, damping: 4.3 N*s/m, force_offset: 0.1 N}
  resistance: 10 ohm
  inductance: {quantity: measure, lambda_l: 2.81 mm, lambda_x: 28.8 mm, lambda_0: 0.433}
  effects: [{type: free_convection, name: still_air, conductance: 0.01 W/K, reference_difference: 50 K}]
drive: {mode: power, power: 1.5 W}
load: {type: deflection, deflection: 20 mm}
)";
  const Trace trace = simulate(yaml);
  // The law written out here, not taken from the component: G dT_ref (|dT|/dT_ref)^(5/4).
  auto convection = [](double rise) { return 0.01 * 50.0 * std::pow(rise / 50.0, 1.25); };
  auto balance = [&](double rise) { return 1.5 - 0.01 * rise - convection(rise); };
  double low = 0.0, high = 100.0;  // balance(low) > 0 > balance(high)
  for (int i = 0; i < 200; ++i)
    (balance(0.5 * (low + high)) > 0.0 ? low : high) = 0.5 * (low + high);
  const double rise = 0.5 * (low + high);  // 71.63 K; a linear law would give 75 K, 4/3 70.68 K
  const double final_rise = trace["muscle/temperature"].back() - 296.15;
  CHECK(final_rise == Approx(rise).epsilon(1e-6));
  CHECK(trace["muscle/still_air/heat_loss"].back() == Approx(convection(final_rise)).epsilon(1e-9));
  // The component's law at fixed points, below ambient too: it carries heat in, not out.
  const FreeConvectionParameters still_air{0.01, 50.0};
  CHECK(FreeConvection::heat_loss(still_air, 50.0) == Approx(0.5).epsilon(1e-15));
  CHECK(FreeConvection::heat_loss(still_air, 100.0) == Approx(0.5 * std::pow(2.0, 1.25)));
  CHECK(FreeConvection::heat_loss(still_air, -50.0) == Approx(-0.5).epsilon(1e-15));
  CHECK(FreeConvection::heat_loss(still_air, 0.0) == 0.0);
  for (std::size_t k = 0; k < trace.time.size(); ++k) {
    const double stored = 0.3 * (trace["muscle/temperature"][k] - 296.15);
    REQUIRE(trace["muscle/heat_in"][k] ==
            Approx(stored + trace["muscle/heat_lost"][k]).margin(allowed(1e-10, 100.0)));
  }
}

TEST_CASE(
    "A heat term attached to the reduced form (7.1) heats as in the physical form it maps from") {
  // kappa_P = phi_T / C and kappa_c = hA / C: the reduced form with the convection taking its
  // share of the power, kappa_P (P - Q), is the physical heat balance divided by C / phi_T.
  const std::string rest = R"(
  mechanics: {k1: 10.8 N/m, k2: 2.7 N/m, damping: 4.3 N*s/m, force_offset: 0.1 N}
  resistance: 10 ohm
  inductance: {quantity: measure, lambda_l: 2.81 mm, lambda_x: 28.8 mm, lambda_0: 0.433}
  effects: [{type: free_convection, name: still_air, conductance: 0.01 W/K, reference_difference: 50 K}]
drive: {mode: power, power: {type: steps, initial: 1.5 W, times: [100 s], values: [0.5 W]}}
load: {type: deflection, deflection: 20 mm}
)";
  const std::string header = R"(scenario: {name: test, duration: 300 s}
output: {rate: 1 Hz}
solver: {rtol: 1.0e-10}
muscle:)";
  const Trace physical = simulate(header + R"(
  thermal: {heat_capacity: 0.3 J/K, conductance: 0.01 W/K, ambient_temperature: 23 degC}
  thermal_force: {form: physical, force_per_kelvin: 0.004 N/K, reference_temperature: 23 degC})" +
                                  rest);
  const Trace reduced = simulate(header + R"(
  thermal_force: {form: reduced, kappa_P: 0.013333333333333334 N/J, kappa_c: 0.033333333333333333 1/s, ambient_temperature: 23 degC, force_per_kelvin: 0.004 N/K})" +
                                 rest);
  CHECK(physical["muscle/temperature"].back() > 296.15 + 20.0);
  // Tens of CVODE's error weight on the node's temperature, rtol |T| + atol (1e-6 K); the heat
  // loss moves by dQ/dT < 0.02 W/K with it.
  const double temperature_bound = 50.0 * (1e-10 * 330.0 + 1e-6);
  CHECK(max_abs_difference(physical["muscle/temperature"], reduced["muscle/temperature"]) <=
        temperature_bound);
  CHECK(max_abs_difference(physical["muscle/still_air/heat_loss"],
                           reduced["muscle/still_air/heat_loss"]) <= 0.02 * temperature_bound);
}

TEST_CASE("Effects are checked against the muscle they attach to") {
  const std::string load = "load: {type: deflection, deflection: 20 mm}\n";
  CHECK_THAT(
      config_error(passive_muscle("  effects: [{type: free_convection, conductance: 0.01 W/K, "
                                  "reference_difference: 50 K}]\n",
                                  load)),
      Catch::Contains("free convection needs the muscle's temperature"));
  CHECK_THAT(
      config_error(passive_muscle("  effects: [{type: maxwell_brunch}]\n", load)),
      Catch::Contains(
          "muscle.effects[0].type: expected one of maxwell_branch, free_convection, "
          "thermal_softening, hysteresis, nonlinear_stiffness, thermal_lag, "
          "heating_lag, heat_sink, ratchet, heating_convection, got 'maxwell_brunch' (did you mean "
          "'maxwell_branch'?)"));
  CHECK_THAT(config_error(passive_muscle(
                 "  effects: [{type: maxwell_branch, stiffness: 1 N/m, damping: 1 N*s/m}, "
                 "{type: maxwell_branch, stiffness: 2 N/m, damping: 1 N*s/m}]\n",
                 load)),
             Catch::Contains("two effects of muscle are named 'maxwell_branch'"));
  CHECK(config_error(passive_muscle(kBranch, load)) == "no error");
}
