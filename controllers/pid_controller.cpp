#include "controllers/pid_controller.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "sim/time_grid.h"

namespace tcpmsim {

namespace {
double idle_power(const PidSettings& settings) {
  return settings.initial_power.value_or(settings.power_min);
}
}  // namespace

DiscretePid::DiscretePid(PidSettings settings, double period)
    : settings_(settings), period_(period) {
  const auto& g = settings_.gains;
  if (!(period_ > 0.0) || !std::isfinite(period_))
    throw std::invalid_argument("PID: the sample period must be positive");
  if (g.proportional == 0.0 || !std::isfinite(g.proportional))
    throw std::invalid_argument("PID: the proportional gain must be finite and non-zero");
  if (!(g.integral_time > 0.0))
    throw std::invalid_argument("PID: the integral time must be positive (infinity: none)");
  if (!(g.derivative_time >= 0.0) || !std::isfinite(g.derivative_time))
    throw std::invalid_argument("PID: the derivative time must be finite and non-negative");
  if (!(settings_.power_min < settings_.power_max))
    throw std::invalid_argument("PID: power limits must satisfy P_min < P_max");
  if (settings_.initial_power) {
    if (!std::isfinite(g.integral_time))
      throw std::invalid_argument("PID: a bumpless start needs integral action");
    if (*settings_.initial_power < settings_.power_min ||
        *settings_.initial_power > settings_.power_max)
      throw std::invalid_argument("PID: the initial power lies outside the power limits");
  }
}

DiscretePid::Step DiscretePid::update(double reference, double reference_slope, double estimate) {
  return update(reference, reference_slope, estimate, settings_.power_min, settings_.power_max);
}

DiscretePid::Step DiscretePid::update(double reference, double reference_slope, double estimate,
                                      double lower, double upper) {
  const auto& g = settings_.gains;
  const bool integrating = std::isfinite(g.integral_time);
  const double error = reference - estimate;
  double derivative = 0.0;
  if (g.derivative_time > 0.0) {
    // Backward difference of the estimate; the first sample has no predecessor and takes the
    // estimate as steady.
    const double estimate_rate = started_ ? (estimate - previous_estimate_) / period_ : 0.0;
    const double reference_rate =
        settings_.derivative == PidSettings::Derivative::error ? reference_slope : 0.0;
    derivative = reference_rate - estimate_rate;
  }
  if (!started_) {
    integral_ = 0.0;
    if (settings_.initial_power) {
      // P_d[0] = initial power: I = T_i (P_0 / K_p - e - T_d de/dt).
      integral_ = g.integral_time * (*settings_.initial_power / g.proportional - error -
                                     g.derivative_time * derivative);
    }
    started_ = true;
  }
  const double integral_term = integrating ? integral_ / g.integral_time : 0.0;
  const double demand =
      g.proportional * (error + g.derivative_time * derivative + integral_term);  // (7.7)
  const double command = std::max(lower, std::min(upper, demand));                // (7.9)
  if (integrating) {
    const double z =
        settings_.anti_windup ? error - (demand - command) / g.proportional : error;  // (7.8)
    integral_ += period_ * z;  // explicit Euler
  }
  previous_estimate_ = estimate;
  return {reference, error, demand, command};
}

void DiscretePid::reset() {
  started_ = false;
  integral_ = 0.0;
  previous_estimate_ = 0.0;
}

// A run's law (with its integral) and what the controller holds between samples.
struct PidController::Run final : RunState {
  Run(const PidSettings& settings, double period)
      : law(settings, period),
        command(idle_power(settings)),
        demand(idle_power(settings)),
        held_reference(std::numeric_limits<double>::quiet_NaN()) {}
  void hold_idle() { command = demand = idle_power(law.settings()); }
  DiscretePid law;
  long last_index = 0;
  bool sampled = false;
  double command;
  double demand;
  double held_reference;
};

PidController::PidController(std::string group, Target target, PidSettings settings,
                             std::unique_ptr<Signal> reference, double period)
    : PidController(std::move(group), target, settings, std::move(reference), period, {}) {}

PidController::PidController(std::string group, Target target, PidSettings settings,
                             std::unique_ptr<Signal> reference, double period,
                             ParameterBindings<PidSettings> bindings)
    : SampledComponent(std::move(group), "pid_controller", period, SamplingStage::controller),
      target_(target),
      defaults_(settings),
      bindings_(std::move(bindings)),
      reference_(std::move(reference)) {
  DiscretePid check(defaults_, period);  // throws for impossible settings
  if (!reference_) throw std::invalid_argument("PID: no reference signal");
}

void read_pid_settings(const ConfigNode& node, std::string_view gain_unit, PidSettings& s,
                       ParameterBindings<PidSettings>& bind) {
  using P = PidSettings;
  read_pid_gains(node, gain_unit, s, bind);
  bind.interval(node, "power_limits", "W", ValueCheck::non_negative(), s,
                bind.member(&P::power_min), bind.member(&P::power_max));
}

void read_pid_gains(const ConfigNode& node, std::string_view gain_unit, PidSettings& s,
                    ParameterBindings<PidSettings>& bind) {
  using P = PidSettings;
  const ConfigNode gains = node.at("gains");
  gains.declare({"proportional", "integral_time", "derivative_time"});
  bind.quantity(
      gains, "proportional", gain_unit, {}, s, [](P& v) -> double& { return v.gains.proportional; },
      [](double value) {
        return value == 0.0 ? std::string("expected a non-zero gain ((7.8) divides by it)")
                            : std::string();
      });
  bind.quantity(gains, "integral_time", "s", ValueCheck::positive(), s,
                [](P& v) -> double& { return v.gains.integral_time; });
  bind.quantity_or(gains, "derivative_time", "s", 0.0, ValueCheck::non_negative(), s,
                   [](P& v) -> double& { return v.gains.derivative_time; });
  s.anti_windup = node.boolean_or("anti_windup", true);
  s.derivative = node.choice_or("derivative_on", {"error", "measurement"}, "error") == "measurement"
                     ? PidSettings::Derivative::measurement
                     : PidSettings::Derivative::error;
}

std::unique_ptr<PidController> PidController::from_config(const std::string& group,
                                                          const ConfigNode& node, double period,
                                                          const SignalContext& signals) {
  using P = PidSettings;
  node.declare({"target", "reference", "gains", "power_limits", "anti_windup", "derivative_on",
                "initial_power"});
  const Target target = node.choice("target", {"deflection", "force"}) == "force"
                            ? Target::force
                            : Target::deflection;
  const char* unit = target == Target::force ? "N" : "m";
  auto reference = read_signal(node.at("reference"), unit, signals);

  P s;
  ParameterBindings<P> bind;
  read_pid_settings(node, target == Target::force ? "W/N" : "W/m", s, bind);
  if (const auto initial = node.find("initial_power")) {
    const double power = initial->as_quantity("W");
    if (power < s.power_min || power > s.power_max)
      initial->fail("expected a power within power_limits");
    s.initial_power = power;
    bind.bind(initial->parameter_path(), "W", {}, [](P& v) -> double& { return *v.initial_power; });
  }
  return std::make_unique<PidController>(group, target, s, std::move(reference), period,
                                         std::move(bind));
}

std::vector<OutputDeclaration> PidController::outputs() const {
  return {{"power_command", "W"},
          {"power_demand", "W"},
          {"reference", target_ == Target::force ? "N" : "m"}};
}

std::vector<ParameterDeclaration> PidController::parameters() const {
  return with_period(bindings_.declarations(defaults_));
}

std::vector<SignalDeclaration> PidController::signals() const {
  return {{"reference", target_ == Target::force ? "N" : "m", reference_.get()}};
}

std::unique_ptr<RunState> PidController::create_run_state(const RunSetup& setup) const {
  return std::make_unique<Run>(bindings_.assign(defaults_, own_parameters(setup)),
                               setup.parameters[0]);
}

std::string pid_settings_problem(const PidSettings& settings, double period) {
  try {
    DiscretePid check(settings, period);
  } catch (const std::exception& error) {
    return error.what();
  }
  return {};
}

std::string PidController::check_parameters(const RunSetup& setup) const {
  return pid_settings_problem(bindings_.assign(defaults_, own_parameters(setup)),
                              setup.parameters[0]);
}

void PidController::compute_outputs(const Evaluation& evaluation) const {
  const Run& run = run_state<Run>(evaluation);
  set_output(evaluation, kPowerCommand, run.command);
  set_output(evaluation, kPowerDemand, run.demand);
  set_output(evaluation, kReference, run.held_reference);
}

double PidController::reference_at(const Signal& reference, double time) {
  // A reference step within the engine's "same instant" margin is taken to be at the sample.
  return reference.value(time + time_margin(time));
}

double PidController::reference_slope_at(const Signal& reference, double time) {
  return reference.slope(time + time_margin(time));
}

void PidController::sample(const Evaluation& evaluation, long index) const {
  Run& run = mutable_run_state<Run>(evaluation);
  if (!run.sampled || index != run.last_index + 1) {
    run.law.reset();
    run.hold_idle();
  }
  run.sampled = true;
  run.last_index = index;
  const double now = evaluation.time;
  const Signal& reference = signal(evaluation, 0);
  run.held_reference = reference_at(reference, now);
  const double estimate = input(evaluation, kEstimate);
  if (!std::isfinite(estimate)) {
    run.hold_idle();
    return;
  }
  const auto step =
      run.law.update(run.held_reference, reference_slope_at(reference, now), estimate);
  run.command = step.command;
  run.demand = step.demand;
}

}  // namespace tcpmsim
