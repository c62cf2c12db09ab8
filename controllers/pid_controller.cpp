#include "controllers/pid_controller.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <tuple>

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

double DiscretePid::saturate(double demand) const {
  return std::max(settings_.power_min, std::min(settings_.power_max, demand));  // (7.9)
}

DiscretePid::Step DiscretePid::update(double reference, double reference_slope, double estimate) {
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
  const double command = saturate(demand);                                        // (7.9)
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

PidController::PidController(std::string group, Target target, PidSettings settings,
                             std::unique_ptr<Signal> reference, double period)
    : SampledComponent(std::move(group), "pid_controller", period, SamplingStage::controller),
      target_(target),
      law_(settings, period),
      reference_(std::move(reference)),
      command_(idle_power(settings)),
      demand_(idle_power(settings)),
      held_reference_(std::numeric_limits<double>::quiet_NaN()) {
  if (!reference_) throw std::invalid_argument("PID: no reference signal");
}

std::unique_ptr<PidController> PidController::from_config(const std::string& group,
                                                          const ConfigNode& node, double period,
                                                          const SignalContext& signals) {
  node.declare({"target", "reference", "gains", "power_limits", "anti_windup", "derivative_on",
                "initial_power"});
  const Target target = node.choice("target", {"deflection", "force"}) == "force"
                            ? Target::force
                            : Target::deflection;
  const char* unit = target == Target::force ? "N" : "m";
  auto reference = read_signal(node.at("reference"), unit, signals);

  PidSettings s;
  const ConfigNode gains = node.at("gains");
  gains.declare({"proportional", "integral_time", "derivative_time"});
  s.gains.proportional = gains.quantity("proportional", target == Target::force ? "W/N" : "W/m");
  if (s.gains.proportional == 0.0)
    gains.at("proportional").fail("expected a non-zero gain ((7.8) divides by it)");
  s.gains.integral_time = gains.quantity("integral_time", "s", ValueCheck::positive());
  s.gains.derivative_time =
      gains.quantity_or("derivative_time", "s", 0.0, ValueCheck::non_negative());
  std::tie(s.power_min, s.power_max) =
      node.interval("power_limits", "W", ValueCheck::non_negative());
  s.anti_windup = node.boolean_or("anti_windup", true);
  s.derivative = node.choice_or("derivative_on", {"error", "measurement"}, "error") == "measurement"
                     ? PidSettings::Derivative::measurement
                     : PidSettings::Derivative::error;
  if (const auto initial = node.find("initial_power")) {
    const double power = initial->as_quantity("W");
    if (power < s.power_min || power > s.power_max)
      initial->fail("expected a power within power_limits");
    s.initial_power = power;
  }
  return std::make_unique<PidController>(group, target, s, std::move(reference), period);
}

std::vector<OutputDeclaration> PidController::outputs() const {
  return {{"power_command", "W"},
          {"power_demand", "W"},
          {"reference", target_ == Target::force ? "N" : "m"}};
}

void PidController::compute_outputs(const Evaluation& evaluation) const {
  set_output(evaluation, kPowerCommand, command_);
  set_output(evaluation, kPowerDemand, demand_);
  set_output(evaluation, kReference, held_reference_);
}

std::vector<Component::SignalRecord> PidController::signal_records() const {
  return {{"reference", target_ == Target::force ? "N" : "m", reference_.get()}};
}

double PidController::reference_at(double time) const {
  // A reference step within the engine's "same instant" margin is taken to be at the sample.
  return reference_->value(time + time_margin(time));
}

double PidController::reference_slope_at(double time) const {
  return reference_->slope(time + time_margin(time));
}

void PidController::hold_idle() {
  command_ = demand_ = idle_power(law_.settings());
}

void PidController::sample(const Evaluation& evaluation, long index) {
  if (!sampled_ || index != last_index_ + 1) {
    law_.reset();
    hold_idle();
  }
  sampled_ = true;
  last_index_ = index;
  const double now = evaluation.time;
  held_reference_ = reference_at(now);
  const double estimate = input(evaluation, kEstimate);
  if (!std::isfinite(estimate)) {
    hold_idle();
    return;
  }
  const auto step = law_.update(held_reference_, reference_slope_at(now), estimate);
  command_ = step.command;
  demand_ = step.demand;
}

}  // namespace tcpmsim
