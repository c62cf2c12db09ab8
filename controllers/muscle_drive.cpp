#include "controllers/muscle_drive.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "sim/time_grid.h"

namespace tcpmsim {

MuscleDrive::MuscleDrive(std::string group, MuscleDriveParameters parameters,
                         std::unique_ptr<Signal> power_demand)
    : Component(std::move(group), "muscle_drive"),
      parameters_(parameters),
      power_demand_(std::move(power_demand)),
      random_(parameters.seed, "muscle_drive.measurement") {}

std::unique_ptr<MuscleDrive> MuscleDrive::from_config(const std::string& group,
                                                      const ConfigNode& node,
                                                      const SignalContext& signals,
                                                      bool controlled) {
  node.declare({"model", "fidelity", "pwm_frequency", "supply_voltage", "series_resistance",
                "measurement", "power"});
  MuscleDriveParameters p;
  p.fidelity = node.choice_or("fidelity", {"averaged", "switched"}, "averaged") == "switched"
                   ? MuscleDriveParameters::Fidelity::switched
                   : MuscleDriveParameters::Fidelity::averaged;
  p.pwm_frequency = node.quantity_or("pwm_frequency", "Hz", 20.0, ValueCheck::positive());
  p.supply_voltage = node.quantity("supply_voltage", "V", ValueCheck::positive());
  p.series_resistance = node.quantity("series_resistance", "ohm", ValueCheck::non_negative());
  const auto measurement = node.at("measurement");
  measurement.declare({"threshold_current", "path_resistance", "timer_resolution", "timing_noise",
                       "spike_probability", "spike_size"});
  p.threshold_current = measurement.quantity("threshold_current", "A", ValueCheck::positive());
  p.path_resistance =
      measurement.quantity_or("path_resistance", "ohm", 0.0, ValueCheck::non_negative());
  p.timer_resolution =
      measurement.quantity_or("timer_resolution", "s", 0.0, ValueCheck::non_negative());
  p.timing_noise = measurement.quantity_or("timing_noise", "s", 0.0, ValueCheck::non_negative());
  p.spike_probability = measurement.number_or("spike_probability", 0.0, ValueCheck::fraction());
  p.spike_size = measurement.quantity_or("spike_size", "s", 0.0, ValueCheck::non_negative());
  p.seed = signals.seed;
  std::unique_ptr<Signal> demand;
  if (controlled) {
    if (node.has("power"))
      node.at("power").fail("the power comes from the controller; remove drive.power");
  } else {
    const ConfigNode power = node.at("power");
    demand = read_signal(power, "W", signals);
    if (demand->range(0.0, signals.duration).first < 0.0)
      power.fail("the power demand goes negative");
  }
  return std::make_unique<MuscleDrive>(group, p, std::move(demand));
}

std::vector<StateDeclaration> MuscleDrive::states() const {
  if (parameters_.fidelity == MuscleDriveParameters::Fidelity::averaged) return {};
  return {{"current", "A", 1e-7}};
}

std::vector<OutputDeclaration> MuscleDrive::outputs() const {
  return {{"power", "W"}, {"duty", "1"},        {"current", "A"}, {"inductance_measure", "s"},
          {"on", "1"},    {"power_demand", "W"}};
}

std::vector<InputDeclaration> MuscleDrive::inputs() const {
  // The switched current's derivative reads L; the averaged drive reads it only to measure.
  const bool switched = parameters_.fidelity == MuscleDriveParameters::Fidelity::switched;
  std::vector<InputDeclaration> declared{{"heater_resistance", true},
                                         {"inductance", false, !switched}};
  if (!power_demand_) declared.push_back({"power_command", false, true});
  return declared;
}

PwmSupply MuscleDrive::supply() const {
  return {parameters_.supply_voltage, parameters_.series_resistance};
}

double MuscleDrive::decay_time(double inductance, double heater_resistance) const {
  return inductance / (heater_resistance + parameters_.path_resistance) *
         std::log(supply().on_current(heater_resistance) / parameters_.threshold_current);
}

double MuscleDrive::measured(double decay) {
  // A timer counts whole ticks; the hardware adds jitter and, now and then, a spike.
  double value =
      parameters_.timer_resolution > 0.0
          ? parameters_.timer_resolution * std::floor(decay / parameters_.timer_resolution)
          : decay;
  if (parameters_.timing_noise > 0.0) value += parameters_.timing_noise * random_.normal();
  if (parameters_.spike_probability > 0.0 && random_.chance(parameters_.spike_probability)) {
    value += (random_.chance(0.5) ? 1.0 : -1.0) * parameters_.spike_size;
  }
  ++measurements_;
  return value;
}

void MuscleDrive::initialize(const Evaluation&, std::span<double> own_state) const {
  for (double& value : own_state) value = 0.0;
}

void MuscleDrive::at_breakpoint(const Evaluation& evaluation) {
  const double t = evaluation.time;
  if (grid_index_at(t, period())) {
    const double resistance = input(evaluation, kHeaterResistance);
    demand_ = power_demand_ ? power_demand_->value(t) : input(evaluation, kCommand);
    on_fraction_ = std::clamp(demand_ / supply().full_power(resistance), 0.0, 1.0);
    last_on_current_ = supply().on_current(resistance);
    on_until_ = t + on_fraction_ * period();
    // An on-phase too short to be a breakpoint of its own (time_margin) is no on-phase: its
    // end would never be delivered and the current would stay on all period.
    on_ = on_until_ > t + 2.0 * time_margin(t);
  } else if (on_ && same_instant(t, on_until_)) {
    on_ = false;
    switched_off_at_ = t;
    awaiting_decay_ = true;
  }
}

void MuscleDrive::sense(const Evaluation& evaluation) {
  // The averaged drive has no simulated decay: at each period start it reports the decay time
  // of the off-phase just ended from L and R now, before the estimator samples, as the
  // switched drive's located crossing is available by then.
  if (parameters_.fidelity != MuscleDriveParameters::Fidelity::averaged) return;
  // Nothing to report after a period with the current always on, or never on.
  const auto k = grid_index_at(evaluation.time, period());
  if (!k || *k < 1 || on_fraction_ >= 1.0 || on_fraction_ <= 0.0) return;
  measure_ =
      measured(decay_time(input(evaluation, kInductance), input(evaluation, kHeaterResistance)));
}

double MuscleDrive::next_breakpoint_after(double t) const {
  double next = next_grid_instant(t, period());
  if (parameters_.fidelity == MuscleDriveParameters::Fidelity::switched && on_ && on_until_ > t) {
    next = std::min(next, on_until_);
  }
  return next;
}

void MuscleDrive::compute_outputs(const Evaluation& evaluation) const {
  const double resistance = input(evaluation, kHeaterResistance);
  if (parameters_.fidelity == MuscleDriveParameters::Fidelity::averaged) {
    const double power = on_fraction_ * supply().full_power(resistance);  // (7.2)
    set_output(evaluation, kPower, power);
    set_output(evaluation, kCurrent, std::sqrt(power / resistance));  // RMS
  } else {
    const double current = state(evaluation, 0);
    set_output(evaluation, kPower, resistance * current * current);
    set_output(evaluation, kCurrent, current);
  }
  set_output(evaluation, kDuty, std::sqrt(on_fraction_));  // D of (7.2)
  set_output(evaluation, kMeasure, measure_);
  set_output(evaluation, kOn, on_ ? 1.0 : 0.0);
  set_output(evaluation, kDemand, demand_);
}

void MuscleDrive::compute_derivatives(const Evaluation& evaluation, double* derivatives) const {
  if (parameters_.fidelity == MuscleDriveParameters::Fidelity::averaged) return;
  const double resistance = input(evaluation, kHeaterResistance);
  const double current = state(evaluation, 0);
  const double voltage = on_ ? parameters_.supply_voltage : 0.0;
  const double loop_resistance =
      on_ ? parameters_.series_resistance + resistance : resistance + parameters_.path_resistance;
  set_derivative(derivatives, 0,
                 (voltage - loop_resistance * current) / input(evaluation, kInductance));
}

int MuscleDrive::event_count() const {
  return parameters_.fidelity == MuscleDriveParameters::Fidelity::switched ? 1 : 0;
}

void MuscleDrive::event_functions(const Evaluation& evaluation, double* values) const {
  values[0] = state(evaluation, 0) - parameters_.threshold_current;
}

void MuscleDrive::at_event(int, const Evaluation& evaluation) {
  if (!awaiting_decay_ || on_) return;
  awaiting_decay_ = false;
  measure_ = measured(evaluation.time - switched_off_at_);
}

void MuscleDrive::adapt_tolerances(std::span<double> absolute, std::span<double> relative) const {
  if (absolute.empty()) return;
  if (awaiting_decay_) {
    // From switch-off to the threshold the current times the measurement: a relative error e
    // in i shifts the crossing by about e tau (tau = L/R ~ 0.13 us) accumulated over the
    // steps, measured at under 0.2 ns for 1e-4, inside a nanosecond timer tick.
    relative[0] = std::max(relative[0], 1e-4);
    return;
  }
  // Elsewhere the current only heats, through R i^2, and its transients last microseconds of
  // a 50 ms period: near zero, a thousandth of the on-current is ample.
  absolute[0] = std::max(absolute[0], 1e-3 * last_on_current_);
}

std::vector<Component::SignalRecord> MuscleDrive::signal_records() const {
  if (!power_demand_) return {};
  return {{"power", "W", power_demand_.get()}};
}

}  // namespace tcpmsim
