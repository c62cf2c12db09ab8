#include "controllers/fan_controller.h"

#include <algorithm>
#include <limits>

#include "controllers/controller_facts.h"
#include "models/bundle/bundle_kind.h"
#include "sim/scenario_builder.h"

namespace tcpmsim {

namespace {
// The fan's speed: off to full.
constexpr double kSpeedOff = 0.0;
constexpr double kSpeedFull = 1.0;
constexpr double kDefaultSamplePeriod = 0.1;  // [s]
}  // namespace

// A run's law (with its integral) and what the controller holds between samples.
struct FanController::Run final : RunState {
  Run(const PidSettings& settings, double period) : law(settings, period) {}
  DiscretePid law;
  long last_index = 0;
  double speed = kSpeedOff;
  double measured = std::numeric_limits<double>::quiet_NaN();
  double reference = std::numeric_limits<double>::quiet_NaN();
};

FanController::FanController(std::string group, Measure measure, PidSettings settings,
                             ParameterBindings<PidSettings> bindings,
                             std::unique_ptr<Signal> reference, double period)
    : SampledComponent(std::move(group), "fan_controller", period, SamplingStage::controller),
      measure_(measure),
      defaults_(settings),
      bindings_(std::move(bindings)),
      reference_(std::move(reference)) {
  DiscretePid check(defaults_, period);  // throws for impossible settings
  if (!reference_) throw std::invalid_argument("fan controller: no reference signal");
}

std::unique_ptr<FanController> FanController::from_config(const std::string& group,
                                                          const ConfigNode& node,
                                                          const SignalContext& signals) {
  node.declare({"type", "bundle", "measure", "reference", "gains", "sample_period", "anti_windup",
                "derivative_on"});
  const Measure measure = node.choice_or("measure", {"hottest", "mean"}, "hottest") == "mean"
                              ? Measure::mean
                              : Measure::hottest;
  auto reference = read_signal(node.at("reference"), "K", signals);
  PidSettings s;
  ParameterBindings<PidSettings> bind;
  read_pid_gains(node, "1/K", s, bind);
  if (!(s.gains.proportional > 0.0))
    node.at("gains").at("proportional").fail("expected a positive gain: the hotter, the more fan");
  s.power_min = kSpeedOff;
  s.power_max = kSpeedFull;
  const double period =
      node.quantity_or("sample_period", "s", kDefaultSamplePeriod, ValueCheck::positive());
  return std::make_unique<FanController>(group, measure, s, std::move(bind), std::move(reference),
                                         period);
}

std::vector<OutputDeclaration> FanController::outputs() const {
  return {{"fan_speed", "1"}, {"measured_temperature", "K"}, {"reference", "K"}};
}

std::vector<InputDeclaration> FanController::inputs() const {
  return {{"temperatures", false, true, InputArity::many}};
}

std::vector<ParameterDeclaration> FanController::parameters() const {
  return with_period(bindings_.declarations(defaults_));
}

std::vector<SignalDeclaration> FanController::signals() const {
  return {{"reference", "K", reference_.get()}};
}

std::unique_ptr<RunState> FanController::create_run_state(const RunSetup& setup) const {
  return std::make_unique<Run>(bindings_.assign(defaults_, own_parameters(setup)),
                               setup.parameters[0]);
}

std::string FanController::check_parameters(const RunSetup& setup) const {
  const PidSettings settings = bindings_.assign(defaults_, own_parameters(setup));
  if (!(settings.gains.proportional > 0.0))
    return "gains.proportional: expected a positive gain: the hotter, the more fan";
  return pid_settings_problem(settings, setup.parameters[0]);
}

void FanController::compute_outputs(const Evaluation& evaluation) const {
  const Run& run = run_state<Run>(evaluation);
  set_output(evaluation, kFanSpeed, run.speed);
  set_output(evaluation, kMeasuredTemperature, run.measured);
  set_output(evaluation, kReference, run.reference);
}

double FanController::measured(const Evaluation& evaluation) const {
  const int count = source_count(kTemperatures);
  if (measure_ == Measure::mean) return input_sum(evaluation, kTemperatures) / count;
  double hottest = input(evaluation, kTemperatures, 0);
  for (int k = 1; k < count; ++k) hottest = std::max(hottest, input(evaluation, kTemperatures, k));
  return hottest;
}

void FanController::sample(const Evaluation& evaluation, long index) const {
  Run& run = mutable_run_state<Run>(evaluation);
  // Every sample updates the law, so a law not yet started is a first sample.
  if (!run.law.started() || index != run.last_index + 1) run.law.reset();
  run.last_index = index;
  const Signal& reference = signal(evaluation, 0);
  run.reference = PidController::reference_at(reference, evaluation.time);
  run.measured = measured(evaluation);
  // DiscretePid acts on r - y; the fan acts on T - T_ref, so both enter negated.
  const auto step =
      run.law.update(-run.reference, -PidController::reference_slope_at(reference, evaluation.time),
                     -run.measured);
  run.speed = step.command;
}

namespace {

void build_fan_controller(const ConfigNode& node, const std::string& name, ScenarioBuilder& build) {
  const auto& bundle = build.linked(node, "bundle", kBundleCategory);
  const BundleFacts* facts = build.facts<BundleFacts>(bundle.name);
  if (!facts) node.at("bundle").fail("expected a bundle; " + bundle.name + " publishes none");
  if (facts->fan != BundleAir::Fan::commanded) {
    node.at("bundle").fail(
        "the fan of " + bundle.name +
        (facts->fan == BundleAir::Fan::none
             ? " does not exist: give the bundle thermal.fan: {conductance, speed: controller}"
             : " has a prescribed speed: set its thermal.fan.speed to controller"));
  }
  SystemBuilder& system = build.system();
  const std::string port = bundle.name + ".fan_command";
  if (system.is_connected(port))
    node.at("bundle").fail("another controller already commands the fan of " + bundle.name);
  auto& controller = system.add(FanController::from_config(name, node, build.signals()));
  for (const auto& member : facts->members)
    system.connect(controller, "temperatures", member + ".temperature");
  system.connect(port, name + ".fan_speed");
}

const char* kFanExample = R"(scenario: {name: example, duration: 60 s, seed: 1}
output: {rate: 1 Hz}
bundle:
  count: 7
  packing: {layout: hexagonal, pitch: 1.6 mm}
  muscle:
    thermal: {heat_capacity: 0.05 J/K, conductance: 2.5 mW/K, ambient_temperature: 23 degC}
    thermal_force: {form: physical, force_per_kelvin: 4 mN/K, reference_temperature: 23 degC}
    mechanics: {k1: 10.8e-3 N/mm, k2: 2.7e-3 N/mm, damping: 4.3e-3 N*s/mm, force_offset: 0.1 N}
    resistance: 10 ohm
    inductance: {lambda_l: 107.4 uH*mm, lambda_x: 61 mm, lambda_0: 2.67 uH}
  thermal: {shielding: 0.6, fan: {conductance: 6 mW/K, speed: controller}}
  electrical: {wiring: parallel, voltage: 1 V}
load: {type: deflection, bundle: bundle, deflection: 20 mm}
controller:
  type: fan
  bundle: bundle
  measure: hottest
  reference: 50 degC
  gains: {proportional: 0.2 1/K, integral_time: 20 s}
  sample_period: 0.1 s
)";

}  // namespace

void register_fan_controller(KindRegistry& kinds) {
  kinds.add({kControllerCategory,
             "fan",
             "active cooling of a bundle: PI(D) (7.7)-(7.9) from its hottest (or mean) member's "
             "temperature to the fan's speed in [0, 1], sampled",
             {{kFanExample, "controller"}},
             InstanceBuilder(build_fan_controller)});
}

}  // namespace tcpmsim
