// The PID controller with back-calculation anti-windup (thesis (7.7)-(7.9)), alone and closing
// the loop through the self-sensing estimator in the engine.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <numbers>

#include "controllers/pid_controller.h"
#include "controllers/self_sensing_estimator.h"
#include "signals/constant_signal.h"
#include "signals/piecewise_constant_signal.h"
#include "signals/sine_signal.h"
#include "tests/support/test_components.h"
#include "tests/support/test_support.h"

using namespace tcpmsim;
using namespace tcpmsim::testing;

namespace {
constexpr double kPeriod = 0.05;

PidSettings settings(double kp, double ti, double td, double p_min, double p_max) {
  PidSettings s;
  s.gains = {kp, ti, td};
  s.power_min = p_min;
  s.power_max = p_max;
  return s;
}

// The integrator needs a continuous state; these systems are all sampled otherwise.
class Idle final : public Component {
 public:
  Idle() : Component("idle", "idle") {}
  std::vector<StateDeclaration> states() const override { return {{"value", "1", 1e-9}}; }
  void compute_derivatives(const Evaluation&, double* derivatives) const override {
    set_derivative(derivatives, 0, 0.0);
  }
};

// A fixed sequence of estimates, one per sample (NaN first, like an estimator without data).
class ScriptedEstimator final : public SampledComponent {
 public:
  struct Held final : RunState {
    double value = std::numeric_limits<double>::quiet_NaN();
  };
  explicit ScriptedEstimator(std::vector<double> values)
      : SampledComponent("estimator", "scripted", kPeriod, SamplingStage::estimator),
        values_(std::move(values)) {}
  std::vector<OutputDeclaration> outputs() const override { return {{"force", "N"}}; }
  std::unique_ptr<RunState> create_run_state(const RunSetup&) const override {
    return std::make_unique<Held>();
  }
  void compute_outputs(const Evaluation& e) const override {
    set_output(e, 0, run_state<Held>(e).value);
  }

 protected:
  void sample(const Evaluation& e, long index) const override {
    mutable_run_state<Held>(e).value =
        values_[std::min(values_.size() - 1, static_cast<std::size_t>(index))];
  }

 private:
  std::vector<double> values_;
};

// Integrates an assembled test system from 0 to t_end, sampling every period.
MemorySink run(SystemBuilder& builder, double t_end) {
  const auto system = builder.build();
  Context context(*system);
  Integrator integrator(*system, context, {});
  MemorySink sink(*system);
  integrator.run(0.0, t_end, kPeriod, sink);
  return sink;
}

std::vector<double> demands(DiscretePid& pid, const std::vector<double>& estimates,
                            std::vector<double>* commands = nullptr) {
  std::vector<double> result;
  for (const double y : estimates) {
    const auto step = pid.update(0.0, 0.0, y);
    result.push_back(step.demand);
    if (commands) commands->push_back(step.command);
  }
  return result;
}
}  // namespace

TEST_CASE("PID output equals a hand-computed sequence for a known error sequence") {
  // K_p = 2, T_i = 0.5 s, T_d = 0.2 s, T = 0.1 s, r = 0; y = 0, -1, -1, -3, -3 so
  // e = 0, 1, 1, 3, 3 and de/dt = -dy/dt = 0 (first sample), 10, 0, 20, 0.
  //   k  P_d = K_p (e + T_d de + I/T_i)      I after (+ T e)
  //   0  2 (0 + 0   + 0)        = 0          0
  //   1  2 (1 + 2   + 0)        = 6          0.1
  //   2  2 (1 + 0   + 0.1/0.5)  = 2.4        0.2
  //   3  2 (3 + 4   + 0.2/0.5)  = 14.8       0.5
  //   4  2 (3 + 0   + 0.5/0.5)  = 8          0.8
  const std::vector<double> y{0.0, -1.0, -1.0, -3.0, -3.0};
  DiscretePid free(settings(2.0, 0.5, 0.2, -100.0, 100.0), 0.1);
  const auto unsaturated = demands(free, y);
  const std::vector<double> expected{0.0, 6.0, 2.4, 14.8, 8.0};
  for (std::size_t k = 0; k < y.size(); ++k)
    CHECK(unsaturated[k] == Approx(expected[k]).epsilon(1e-12));
  CHECK(free.integral() == Approx(0.8).epsilon(1e-12));

  // Saturated to [0, 5] W with back-calculation, z = e - (P_d - P)/K_p:
  //   k  P_d                               P    z                      I after
  //   0  0                                 0    0                      0
  //   1  2 (1 + 2 + 0)          = 6        5    1 - 1/2     = 0.5      0.05
  //   2  2 (1 + 0 + 0.05/0.5)   = 2.2      2.2  1                      0.15
  //   3  2 (3 + 4 + 0.15/0.5)   = 14.6     5    3 - 9.6/2   = -1.8     -0.03
  //   4  2 (3 + 0 - 0.03/0.5)   = 5.88     5    3 - 0.88/2  = 2.56     0.226
  DiscretePid saturated(settings(2.0, 0.5, 0.2, 0.0, 5.0), 0.1);
  std::vector<double> commands;
  const auto limited = demands(saturated, y, &commands);
  const std::vector<double> expected_demand{0.0, 6.0, 2.2, 14.6, 5.88};
  const std::vector<double> expected_command{0.0, 5.0, 2.2, 5.0, 5.0};
  for (std::size_t k = 0; k < y.size(); ++k) {
    CHECK(limited[k] == Approx(expected_demand[k]).epsilon(1e-12));
    CHECK(commands[k] == Approx(expected_command[k]).epsilon(1e-12));
  }
  CHECK(saturated.integral() == Approx(0.226).epsilon(1e-12));

  // Without back-calculation the demands are the unsaturated ones.
  auto plain = settings(2.0, 0.5, 0.2, 0.0, 5.0);
  plain.anti_windup = false;
  DiscretePid windup(plain, 0.1);
  const auto wound = demands(windup, y);
  for (std::size_t k = 0; k < y.size(); ++k) CHECK(wound[k] == Approx(expected[k]).epsilon(1e-12));

  // T_d = 0 is PI: the same sequence without the derivative terms.
  DiscretePid pi(settings(2.0, 0.5, 0.0, -100.0, 100.0), 0.1);
  const auto pi_demands = demands(pi, y);
  const std::vector<double> expected_pi{0.0, 2.0, 2.4, 6.8, 8.0};
  for (std::size_t k = 0; k < y.size(); ++k)
    CHECK(pi_demands[k] == Approx(expected_pi[k]).epsilon(1e-12));
}

TEST_CASE("Anti-windup keeps the integrator from winding up under saturation") {
  // K_p = 1, T_i = 1 s, P in [0, 1] W. 20 s of error e = 2 saturate the demand; then the
  // error reverses to -0.5 (the response overshot).
  auto run = [](bool anti_windup, double& integral_at_flip) {
    auto s = settings(1.0, 1.0, 0.0, 0.0, 1.0);
    s.anti_windup = anti_windup;
    DiscretePid pid(s, kPeriod);
    for (int k = 0; k < 400; ++k) pid.update(2.0, 0.0, 0.0);
    integral_at_flip = pid.integral();
    int saturated_samples = 0;
    for (int k = 0; k < 4000; ++k) {
      if (pid.update(0.0, 0.0, 0.5).command >= 1.0) ++saturated_samples;
    }
    return saturated_samples;
  };
  double with = 0.0, without = 0.0;
  const int stuck_with = run(true, with);
  const int stuck_without = run(false, without);
  // With back-calculation, at P_max: I[k+1] = I[k] + T (P_max/K_p - I[k]/T_i), so
  // I[k] = T_i P_max/K_p (1 - (1 - T/T_i)^k): it settles at 1, P_d = P_max + K_p e.
  CHECK(with == Approx(1.0 - std::pow(1.0 - kPeriod, 400)).epsilon(1e-12));
  // Without it the integral grows by T e per sample: 2 * 20 s = 40.
  CHECK(without == Approx(40.0).epsilon(1e-12));
  // After the reversal the wound-up controller stays at P_max until I has bled down to 1.5:
  // (40 - 1.5) / (0.05 * 0.5) = 1540 more samples (77 s); the other leaves at once.
  CHECK(stuck_with == 0);
  CHECK(stuck_without >= 1540);
  CHECK(stuck_without <= 1542);
}

TEST_CASE("The derivative ignores reference steps but differentiates a smooth reference") {
  // A reference step with a constant estimate: PID and PI demands are identical (no kick).
  DiscretePid pid(settings(2.0, 1.0, 0.5, -1e3, 1e3), kPeriod);
  DiscretePid pi(settings(2.0, 1.0, 0.0, -1e3, 1e3), kPeriod);
  for (int k = 0; k < 40; ++k) {
    const double r = k < 20 ? 0.0 : 1.0;  // piecewise constant: slope 0
    CHECK(pid.update(r, 0.0, 0.3).demand == Approx(pi.update(r, 0.0, 0.3).demand).epsilon(1e-14));
  }
  // A sine reference with the estimate at rest: P_d = K_p (r + T_d dr/dt) exactly (no
  // integral), and K_p r when the derivative acts on the measurement only.
  auto on_error = settings(2.0, std::numeric_limits<double>::infinity(), 0.5, -1e3, 1e3);
  auto on_measurement = on_error;
  on_measurement.derivative = PidSettings::Derivative::measurement;
  DiscretePid error_pid(on_error, kPeriod), measurement_pid(on_measurement, kPeriod);
  const SineSignal reference(0.0, 1.0, 0.05, 0.0);
  for (int k = 0; k < 100; ++k) {
    const double t = k * kPeriod;
    const double r = reference.value(t), slope = reference.slope(t);
    CHECK(error_pid.update(r, slope, 0.0).demand == Approx(2.0 * (r + 0.5 * slope)).margin(1e-14));
    CHECK(measurement_pid.update(r, slope, 0.0).demand == Approx(2.0 * r).margin(1e-14));
  }
}

TEST_CASE("A bumpless start makes the first demand equal the initial power") {
  auto s = settings(2.0, 0.5, 0.2, 0.0, 5.0);
  s.initial_power = 1.5;
  DiscretePid pid(s, 0.1);
  // e = 1: I = T_i (P_0/K_p - e) = 0.5 (0.75 - 1) = -0.125, P_d = 2 (1 - 0.25) = 1.5.
  CHECK(pid.update(0.0, 0.0, -1.0).demand == Approx(1.5).epsilon(1e-14));
  // Without it the integral starts empty: P_d = K_p e.
  DiscretePid empty(settings(2.0, 0.5, 0.2, 0.0, 5.0), 0.1);
  CHECK(empty.update(0.0, 0.0, -1.0).demand == Approx(2.0).epsilon(1e-14));
}

TEST_CASE("The reference is sampled on the right of a step at the sample instant") {
  // k T and a decimal step time may differ by rounding; the controller must see the new value
  // whenever the engine treats the two as the same instant (64 ulp), and only then.
  auto controller_with_step_at = [](double step_time) {
    return PidController("controller", PidController::Target::force,
                         settings(1.0, 1.0, 0.0, 0.0, 1.0),
                         std::make_unique<PiecewiseConstantSignal>(
                             0.1, std::vector<double>{step_time}, std::vector<double>{0.2}),
                         kPeriod);
  };
  const double instant = 7 * kPeriod;  // 0.35000000000000003
  const auto exact = controller_with_step_at(instant);
  CHECK(exact.reference_at(instant) == 0.2);
  CHECK(exact.reference_at(6 * kPeriod) == 0.1);
  const auto rounded_up =
      controller_with_step_at(std::nextafter(std::nextafter(instant, 1.0), 1.0));
  CHECK(rounded_up.reference_at(instant) == 0.2);
  const auto decimal = controller_with_step_at(0.35);  // one ulp before the instant
  CHECK(decimal.reference_at(instant) == 0.2);
  const auto later = controller_with_step_at(instant + 1e-9);  // a genuinely later step
  CHECK(later.reference_at(instant) == 0.1);
}

TEST_CASE("The controller idles until the estimate is finite, then controls from that sample") {
  SystemBuilder system;
  system.add(std::make_unique<Idle>());
  // NaN for three samples (the estimator waits for the Muscle Drive's first measurement).
  const double nan = std::numeric_limits<double>::quiet_NaN();
  system.add(std::make_unique<ScriptedEstimator>(std::vector<double>{nan, nan, nan, 0.35}));
  auto s = settings(100.0, 1.0, 0.0, 0.1, 3.12);
  auto& controller =
      system.add(std::make_unique<PidController>("controller", PidController::Target::force, s,
                                                 std::make_unique<ConstantSignal>(0.4), kPeriod));
  system.connect(controller, "estimate", "estimator.force");
  const MemorySink sink = run(system, 0.3);
  const auto& command = sink["controller/power_command"];
  for (std::size_t k = 0; k < 3; ++k) CHECK(command[k] == 0.1);  // idle: P_min
  // Then e = 0.05 N: P_d = 100 * 0.05 = 5 W with an empty integral, saturated to 3.12 W.
  CHECK(sink["controller/power_demand"][3] == Approx(5.0).epsilon(1e-12));
  CHECK(command[3] == 3.12);
  CHECK(sink["controller/reference"][3] == 0.4);
}

TEST_CASE("Closed through the estimator, the controller sees the force of its previous command") {
  // Force control at constant deflection, the loop of thesis 7.2.5: the estimator at t_k
  // integrates the power commanded at t_{k-1}; the controller at t_k uses that estimate. The
  // engine's sequence must equal the same recursion written out by hand, bit for bit.
  const auto p = thesis_estimator_parameters();
  const double measure = p.inductance(20e-3, p.inductance.reference_temperature);
  auto control = settings(540.0, 1.0, 0.0, 0.10, 3.12);
  SystemBuilder system;
  system.add(std::make_unique<Idle>());
  system.add(std::make_unique<SignalSource>("drive", std::make_unique<ConstantSignal>(measure)));
  auto& estimator = system.add(std::make_unique<SelfSensingEstimator>("estimator", p, kPeriod));
  auto& controller = system.add(std::make_unique<PidController>(
      "controller", PidController::Target::force, control,
      std::make_unique<PiecewiseConstantSignal>(0.38, std::vector<double>{5.0},
                                                std::vector<double>{0.42}),
      kPeriod));
  system.connect(estimator, "inductance_measure", "drive.value");
  system.connect(estimator, "power_command", "controller.power_command");
  system.connect(controller, "estimate", "estimator.force");
  const MemorySink sink = run(system, 30.0);

  SelfSensingEstimation offline_estimator(p, kPeriod);
  DiscretePid offline_pid(control, kPeriod);
  double command = control.power_min;  // held before the first sample
  for (std::size_t k = 0; k + 1 < sink.time.size(); ++k) {
    const double force = offline_estimator.process(measure, command).force;
    const double reference = k < 100 ? 0.38 : 0.42;
    command = offline_pid.update(reference, 0.0, force).command;
    INFO("sample " << k);
    REQUIRE(sink["controller/power_command"][k] == command);
    REQUIRE(sink["estimator/force"][k] == force);
  }
  // And it settles where (7.1) and (7.5) balance: F = k1 x + phi_0 + kappa_P P / kappa_c
  // (after about 4 s at P_max following each step: the power limit, not the gain, sets the pace).
  const double settled = sink["controller/power_command"][sink.time.size() - 2];
  CHECK(settled == Approx(p.cooling_rate / p.heating_gain *
                          (0.42 - p.mechanics.k1 * 20e-3 - p.mechanics.force_offset))
                       .epsilon(1e-6));
}

TEST_CASE("The controller reads its gains and limits with units") {
  auto load = [](const std::string& yaml) {
    const ConfigNode root = ConfigNode::load_text(yaml, "c.yaml", {}, shared_units());
    const KindRegistry kinds = standard_kinds();
    auto controller = PidController::from_config("controller", root.at("controller"), 0.05,
                                                 {1, 100.0, &kinds, {}});
    root.reject_unknown_keys();
    return controller;
  };
  const auto deflection = load(R"(
controller:
  target: deflection
  reference: {type: steps, initial: 20 mm, times: [20 s], values: [25 mm]}
  gains: {proportional: -1.08 W/mm, integral_time: 2.5 s, derivative_time: 0.625 s}
  power_limits: [0.10 W, 3.12 W]
)");
  const auto& d = deflection->defaults();
  CHECK(deflection->target() == PidController::Target::deflection);
  CHECK(d.gains.proportional == Approx(-1080.0));
  CHECK(d.gains.integral_time == 2.5);
  CHECK(d.gains.derivative_time == 0.625);
  CHECK(d.power_min == Approx(0.10));
  CHECK(d.power_max == Approx(3.12));
  CHECK(d.anti_windup);
  CHECK(d.derivative == PidSettings::Derivative::error);
  CHECK_FALSE(d.initial_power.has_value());
  CHECK(deflection->reference_at(20.0) == Approx(25e-3));
  CHECK(deflection->sampling_stage() == Component::SamplingStage::controller);
  REQUIRE(deflection->signals().size() == 1);
  CHECK(deflection->signals()[0].unit == "m");

  const auto force = load(R"(
controller:
  target: force
  reference: 0.4 N
  gains: {proportional: 540 W/N, integral_time: 1 s}
  power_limits: [0.10 W, 3.12 W]
  anti_windup: false
  derivative_on: measurement
  initial_power: 1.4 W
)");
  const auto& f = force->defaults();
  CHECK(f.gains.proportional == Approx(540.0));
  CHECK(f.gains.derivative_time == 0.0);
  CHECK_FALSE(f.anti_windup);
  CHECK(f.derivative == PidSettings::Derivative::measurement);
  CHECK(f.initial_power == Approx(1.4));

  auto error_of = [&](const std::string& yaml) {
    try {
      load(yaml);
    } catch (const ConfigError& error) {
      return std::string(error.what());
    }
    return std::string("no error");
  };
  const std::string base = R"(
controller:
  target: force
  reference: 0.4 N
  power_limits: [0.10 W, 3.12 W]
)";
  CHECK_THAT(error_of(base + "  gains: {proportional: 0 W/N, integral_time: 1 s}\n"),
             Catch::Contains("controller.gains.proportional: expected a non-zero gain"));
  CHECK_THAT(error_of(base + "  gains: {proportional: 540 W/mm, integral_time: 1 s}\n"),
             Catch::Contains("controller.gains.proportional"));
  CHECK_THAT(error_of(base + "  gains: {proportional: 540 W/N, integral_time: 1 s}\n"
                             "  initial_power: 4 W\n"),
             Catch::Contains("controller.initial_power: expected a power within power_limits"));
}
