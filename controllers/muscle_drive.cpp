#include "controllers/muscle_drive.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "models/typical_values.h"
#include "sim/context.h"
#include "sim/time_grid.h"

namespace tcpmsim {

namespace {

PwmSupply supply_of(const MuscleDriveParameters& p) {
  return {p.supply_voltage, p.series_resistance};
}

std::string demand_problem(const Signal& demand, double duration) {
  return demand.range(0.0, duration).first < 0.0 ? "the power demand goes negative" : "";
}
}  // namespace

// A run's parameters, its random stream and what the drive holds between instants.
struct MuscleDrive::Run final : RunState {
  explicit Run(const MuscleDriveParameters& values)
      : p(values), random(values.seed, values.stream) {}
  double period() const { return 1.0 / p.pwm_frequency; }
  // Quantisation, noise, spikes.
  double measured(double decay_time);

  MuscleDriveParameters p;
  RandomStream random;
  // Held from the latest period start / switching edge.
  double last_on_current = 0.0;
  double on_fraction = 0.0;  // D^2 = P / P_full, in [0, 1]
  double demand = 0.0;       // the power asked for this period [W]
  double on_until = 0.0;     // end of this period's on-phase [s]
  bool on = false;
  double switched_off_at = -1.0;
  bool awaiting_decay = false;
  double measure = 0.0;  // L* [s]
  long measurements = 0;
};

double MuscleDrive::Run::measured(double decay) {
  // A timer counts whole ticks; the hardware adds jitter and, now and then, a spike.
  double value = p.timer_resolution > 0.0
                     ? p.timer_resolution * std::floor(decay / p.timer_resolution)
                     : decay;
  if (p.timing_noise > 0.0) value += p.timing_noise * random.normal();
  if (p.spike_probability > 0.0 && random.chance(p.spike_probability)) {
    value += (random.chance(0.5) ? 1.0 : -1.0) * p.spike_size;
  }
  ++measurements;
  return value;
}

MuscleDrive::MuscleDrive(std::string group, MuscleDriveParameters defaults,
                         ParameterBindings<MuscleDriveParameters> bindings,
                         std::unique_ptr<Signal> power_demand, double demand_duration)
    : Component(std::move(group), "muscle_drive"),
      defaults_(std::move(defaults)),
      bindings_(std::move(bindings)),
      power_demand_(std::move(power_demand)),
      demand_duration_(demand_duration) {}

std::unique_ptr<MuscleDrive> MuscleDrive::from_config(const std::string& group,
                                                      const ConfigNode& node,
                                                      const SignalContext& signals) {
  node.declare({"model", "fidelity", "pwm_frequency", "supply_voltage", "series_resistance",
                "measurement", "power"});
  MuscleDriveParameters p;
  ParameterBindings<MuscleDriveParameters> bind;
  p.fidelity = node.choice_or("fidelity", {"averaged", "switched"}, "averaged") == "switched"
                   ? MuscleDriveParameters::Fidelity::switched
                   : MuscleDriveParameters::Fidelity::averaged;
  bind.quantity_or(node, "pwm_frequency", "Hz", 20.0, ValueCheck::positive(), p,
                   bind.member(&MuscleDriveParameters::pwm_frequency));
  bind.quantity(node, "supply_voltage", "V", typical::supply_voltage(ValueCheck::positive()), p,
                bind.member(&MuscleDriveParameters::supply_voltage));
  bind.quantity(node, "series_resistance", "ohm", ValueCheck::non_negative(), p,
                bind.member(&MuscleDriveParameters::series_resistance));
  const auto measurement = node.at("measurement");
  measurement.declare({"threshold_current", "path_resistance", "timer_resolution", "timing_noise",
                       "spike_probability", "spike_size"});
  bind.quantity(measurement, "threshold_current", "A", ValueCheck::positive(), p,
                bind.member(&MuscleDriveParameters::threshold_current));
  bind.quantity_or(measurement, "path_resistance", "ohm", 0.0, ValueCheck::non_negative(), p,
                   bind.member(&MuscleDriveParameters::path_resistance));
  bind.quantity_or(measurement, "timer_resolution", "s", 0.0, ValueCheck::non_negative(), p,
                   bind.member(&MuscleDriveParameters::timer_resolution));
  bind.quantity_or(measurement, "timing_noise", "s", 0.0, ValueCheck::non_negative(), p,
                   bind.member(&MuscleDriveParameters::timing_noise));
  bind.quantity_or(measurement, "spike_probability", "1", 0.0, ValueCheck::fraction(), p,
                   bind.member(&MuscleDriveParameters::spike_probability));
  bind.quantity_or(measurement, "spike_size", "s", 0.0, ValueCheck::non_negative(), p,
                   bind.member(&MuscleDriveParameters::spike_size));
  p.seed = signals.seed;
  // The drive of the single-muscle scenario keeps its historical stream, so that its records
  // stay what they were; every other drive has its own.
  if (group != "drive") p.stream = group + ".muscle_drive.measurement";
  std::unique_ptr<Signal> demand;  // none: a controller commands the power
  if (const auto power = node.find("power")) {
    demand = read_signal(*power, "W", signals);
    if (std::string problem = demand_problem(*demand, signals.duration); !problem.empty())
      power->fail(problem);
  }
  return std::make_unique<MuscleDrive>(group, p, std::move(bind), std::move(demand),
                                       signals.duration);
}

std::vector<StateDeclaration> MuscleDrive::states() const {
  if (defaults_.fidelity == MuscleDriveParameters::Fidelity::averaged) return {};
  return {{"current", "A", 1e-7}};
}

std::vector<OutputDeclaration> MuscleDrive::outputs() const {
  return {{"power", "W"}, {"duty", "1"},        {"current", "A"}, {"inductance_measure", "s"},
          {"on", "1"},    {"power_demand", "W"}};
}

std::vector<InputDeclaration> MuscleDrive::inputs() const {
  // The switched current's derivative reads L; the averaged drive reads it only to measure.
  const bool switched = defaults_.fidelity == MuscleDriveParameters::Fidelity::switched;
  std::vector<InputDeclaration> declared{{"heater_resistance", true},
                                         {"inductance", false, !switched}};
  if (!power_demand_) declared.push_back({"power_command", false, true});
  return declared;
}

std::vector<ParameterDeclaration> MuscleDrive::parameters() const {
  return bindings_.declarations(defaults_);
}

std::vector<SignalDeclaration> MuscleDrive::signals() const {
  if (!power_demand_) return {};
  return {{"power", "W", power_demand_.get()}};
}

std::unique_ptr<RunState> MuscleDrive::create_run_state(const RunSetup& setup) const {
  return std::make_unique<Run>(bindings_.assign(defaults_, setup.parameters));
}

std::string MuscleDrive::check_parameters(const RunSetup& setup) const {
  if (!power_demand_) return {};
  const std::string problem = demand_problem(signal(setup.context, 0), demand_duration_);
  return problem.empty() ? problem : "power: " + problem;
}

void MuscleDrive::initialize(const Evaluation&, std::span<double> own_state) const {
  for (double& value : own_state) value = 0.0;
}

void MuscleDrive::at_breakpoint(const Evaluation& evaluation) const {
  Run& run = mutable_run_state<Run>(evaluation);
  const double t = evaluation.time;
  if (grid_index_at(t, run.period())) {
    const double resistance = input(evaluation, kHeaterResistance);
    run.demand = power_demand_ ? signal(evaluation, 0).value(t) : input(evaluation, kCommand);
    run.on_fraction = std::clamp(run.demand / supply_of(run.p).full_power(resistance), 0.0, 1.0);
    run.last_on_current = supply_of(run.p).on_current(resistance);
    run.on_until = t + run.on_fraction * run.period();
    // An on-phase too short to be a breakpoint of its own (time_margin) is no on-phase: its
    // end would never be delivered and the current would stay on all period.
    run.on = run.on_until > t + 2.0 * time_margin(t);
  } else if (run.on && same_instant(t, run.on_until)) {
    run.on = false;
    run.switched_off_at = t;
    run.awaiting_decay = true;
  }
}

void MuscleDrive::sense(const Evaluation& evaluation) const {
  // The averaged drive has no simulated decay: at each period start it reports the decay time
  // of the off-phase just ended from L and R now, before the estimator samples, as the
  // switched drive's located crossing is available by then.
  Run& run = mutable_run_state<Run>(evaluation);
  if (run.p.fidelity != MuscleDriveParameters::Fidelity::averaged) return;
  // Nothing to report after a period with the current always on, or never on.
  const auto k = grid_index_at(evaluation.time, run.period());
  if (!k || *k < 1 || run.on_fraction >= 1.0 || run.on_fraction <= 0.0) return;
  const double heater = input(evaluation, kHeaterResistance);
  run.measure =
      run.measured(decay_time(input(evaluation, kInductance), heater, run.p.path_resistance,
                              supply_of(run.p).on_current(heater), run.p.threshold_current));
}

double MuscleDrive::next_breakpoint_after(const Evaluation& evaluation) const {
  const Run& run = run_state<Run>(evaluation);
  const double t = evaluation.time;
  double next = next_grid_instant(t, run.period());
  if (run.p.fidelity == MuscleDriveParameters::Fidelity::switched && run.on && run.on_until > t) {
    next = std::min(next, run.on_until);
  }
  return next;
}

void MuscleDrive::compute_outputs(const Evaluation& evaluation) const {
  const Run& run = run_state<Run>(evaluation);
  const double resistance = input(evaluation, kHeaterResistance);
  if (run.p.fidelity == MuscleDriveParameters::Fidelity::averaged) {
    const double power = run.on_fraction * supply_of(run.p).full_power(resistance);  // (7.2)
    set_output(evaluation, kPower, power);
    set_output(evaluation, kCurrent, std::sqrt(power / resistance));  // RMS
  } else {
    const double current = state(evaluation, 0);
    set_output(evaluation, kPower, resistance * current * current);
    set_output(evaluation, kCurrent, current);
  }
  set_output(evaluation, kDuty, std::sqrt(run.on_fraction));  // D of (7.2)
  set_output(evaluation, kMeasure, run.measure);
  set_output(evaluation, kOn, run.on ? 1.0 : 0.0);
  set_output(evaluation, kDemand, run.demand);
}

void MuscleDrive::compute_derivatives(const Evaluation& evaluation, double* derivatives) const {
  const Run& run = run_state<Run>(evaluation);
  if (run.p.fidelity == MuscleDriveParameters::Fidelity::averaged) return;
  const double resistance = input(evaluation, kHeaterResistance);
  const double current = state(evaluation, 0);
  const double voltage = run.on ? run.p.supply_voltage : 0.0;
  const double loop_resistance =
      run.on ? run.p.series_resistance + resistance : resistance + run.p.path_resistance;
  set_derivative(derivatives, 0,
                 (voltage - loop_resistance * current) / input(evaluation, kInductance));
}

int MuscleDrive::event_count() const {
  return defaults_.fidelity == MuscleDriveParameters::Fidelity::switched ? 1 : 0;
}

void MuscleDrive::event_functions(const Evaluation& evaluation, double* values) const {
  values[0] = state(evaluation, 0) - run_state<Run>(evaluation).p.threshold_current;
}

void MuscleDrive::at_event(int, const Evaluation& evaluation) const {
  Run& run = mutable_run_state<Run>(evaluation);
  if (!run.awaiting_decay || run.on) return;
  run.awaiting_decay = false;
  run.measure = run.measured(evaluation.time - run.switched_off_at);
}

void MuscleDrive::adapt_tolerances(const Evaluation& evaluation, std::span<double> absolute,
                                   std::span<double> relative) const {
  if (absolute.empty()) return;
  const Run& run = run_state<Run>(evaluation);
  if (run.awaiting_decay) {
    // From switch-off to the threshold the current times the measurement: a relative error e
    // in i shifts the crossing by about e tau (tau = L/R ~ 0.13 us) accumulated over the
    // steps, measured at under 0.2 ns for 1e-4, inside a nanosecond timer tick.
    relative[0] = std::max(relative[0], 1e-4);
    return;
  }
  // Elsewhere the current only heats, through R i^2, and its transients last microseconds of
  // a 50 ms period: near zero, a thousandth of the on-current is ample.
  absolute[0] = std::max(absolute[0], 1e-3 * run.last_on_current);
}

}  // namespace tcpmsim
