#include "controllers/controller_kinds.h"

#include "controllers/controller_facts.h"
#include "controllers/external_controller.h"
#include "controllers/fan_controller.h"
#include "controllers/joint_controller_kind.h"
#include "controllers/joule_drive.h"
#include "controllers/muscle_drive.h"
#include "controllers/pid_controller.h"
#include "controllers/self_sensing_estimator.h"
#include "models/bundle/bundle_magnetics.h"
#include "models/muscle.h"
#include "sim/scenario_builder.h"

namespace tcpmsim {

namespace {

void build_joule_drive(const ConfigNode& node, const std::string& name, ScenarioBuilder& build) {
  node.declare({"muscle"});
  const auto& muscle = build.linked(node, "muscle", kMuscleCategory);
  SystemBuilder& system = build.system();
  auto& drive = system.add(JouleDrive::from_config(name, node, build.signals()));
  system.connect(muscle.name + ".power", name + ".power");
  if (drive.needs_resistance())
    system.connect(drive, "heater_resistance", muscle.name + ".resistance");
}

void build_muscle_drive(const ConfigNode& node, const std::string& name, ScenarioBuilder& build) {
  node.declare({"muscle"});
  const auto& muscle = build.linked(node, "muscle", kMuscleCategory);
  if (!build.facts<MuscleFacts>(muscle.name)->has_inductance) {
    node.fail("the Muscle Drive measures the coil's inductance (self-sensing), but " +
              muscle.node.path() + " states none: give " + muscle.node.path() +
              ".inductance, (6.3) in henries");
  }
  if (build.facts<MuscleFacts>(muscle.name)->inductance_is_measure) {
    node.fail("the Muscle Drive measures the coil's decay time itself: give " + muscle.node.path() +
              ".inductance in henries (quantity: inductance), not as a measure");
  }
  // Without a power signal a controller commands it (checked once every instance is built).
  const bool takes_command = !node.has("power");
  SystemBuilder& system = build.system();
  auto& drive = system.add(MuscleDrive::from_config(name, node, build.signals()));
  system.connect(drive, "heater_resistance", muscle.name + ".resistance");
  system.connect(drive, "inductance", muscle.name + ".inductance");
  system.connect(muscle.name + ".power", name + ".power");
  if (takes_command) {
    system.export_input(name + ".power_command", drive, "power_command");
    build.after_building([node, name, &system] {
      if (!system.is_connected(name + ".power_command")) node.at("power");  // "missing power"
    });
  }
  build.publish(name, MuscleDriveFacts{1.0 / drive.defaults().pwm_frequency, takes_command, node,
                                       muscle.name});
}

// The estimator's own model of a bundle member's coupling to its neighbours, G n M(x) in L*:
// its own coil geometry and G (measure_per_henry), the packing's neighbours and pitch. Members
// sharing one section share one table.
std::function<double(double)> mutual_model(const ConfigNode& node, const std::string& muscle,
                                           ScenarioBuilder& build) {
  const auto* coupling = build.facts<MemberCouplingFacts>(muscle + "/magnetic");
  if (!coupling) {
    node.fail("models a bundle member's coupling to its neighbours; the muscle " + muscle +
              " has none (give the bundle a magnetic section)");
  }
  node.declare({"coil", "measure_per_henry"});
  const double gain = node.quantity("measure_per_henry", "s/H", ValueCheck::positive());
  using Model = std::shared_ptr<const NeighbourMutual>;
  const std::string key = node.path() + " at pitch " + std::to_string(coupling->pitch);
  const Model* shared = build.facts<Model>(key);
  const Model model = shared ? *shared : NeighbourMutual::from_config(node, coupling->pitch);
  if (!shared) build.publish(key, model);
  const double neighbours = coupling->neighbours;
  return [model, gain, neighbours](double deflection) {
    return gain * neighbours * (*model)(deflection);
  };
}

void build_estimator(const ConfigNode& node, const std::string& name, ScenarioBuilder& build) {
  node.declare({"drive", "mutual_compensation"});
  const auto& drive = build.linked(node, "drive", kDriveCategory);
  const MuscleDriveFacts& facts = sensing_drive(node, drive.name, build);
  SystemBuilder& system = build.system();
  std::function<double(double)> mutual;
  if (const auto compensation = node.find("mutual_compensation"))
    mutual = mutual_model(*compensation, facts.muscle, build);
  auto& estimator = system.add(SelfSensingEstimator::from_config(name, node, facts.period, mutual));
  system.connect(estimator, "inductance_measure", drive.name + ".inductance_measure");
  // The power asked of the drive over the period that ends at the sample: a controller's
  // command of the previous sample, or the drive's own demand.
  system.connect(estimator, "power_command", drive.name + ".power_demand");
  follow_pwm(build, name, drive.name);
  build.publish(name, EstimatorFacts{drive.name});
}

void build_controller(const ConfigNode& node, const std::string& name, ScenarioBuilder& build) {
  node.declare({"estimator"});
  if (build.instances(kEstimatorCategory).empty()) {
    bool any_muscle_drive = false;
    for (const auto* drive : build.instances(kDriveCategory))
      any_muscle_drive = any_muscle_drive || build.facts<MuscleDriveFacts>(drive->name);
    node.fail(any_muscle_drive ? "a controller needs an estimator section to read"
                               : "self-sensing needs the Muscle Drive (drive.model: muscle_drive)");
  }
  const auto& estimator = build.linked(node, "estimator", kEstimatorCategory);
  const std::string drive = build.facts<EstimatorFacts>(estimator.name)->drive;
  const MuscleDriveFacts& facts = sensing_drive(node, drive, build);
  check_takes_command(facts);
  SystemBuilder& system = build.system();
  auto& controller =
      system.add(PidController::from_config(name, node, facts.period, build.signals()));
  system.connect(
      controller, "estimate",
      estimator.name +
          (controller.target() == PidController::Target::deflection ? ".deflection" : ".force"));
  system.connect(drive + ".power_command", name + ".power_command");
  follow_pwm(build, name, drive);
}

void build_external_controller(const ConfigNode& node, const std::string& name,
                               ScenarioBuilder& build) {
  node.declare({"drive"});
  const auto& drive = build.linked(node, "drive", kDriveCategory);
  const auto* facts = build.facts<MuscleDriveFacts>(drive.name);
  if (!facts)
    node.fail("an external controller commands a Muscle Drive's power (drive.model: muscle_drive)");
  check_takes_command(*facts);
  SystemBuilder& system = build.system();
  system.add(ExternalController::from_config(name, node, build.signals()));
  system.connect(drive.name + ".power_command", name + ".power_command");
}

std::string with_drive(const std::string& drive, const std::string& more = "") {
  return example_muscle_scenario("",
                                 drive + more + "load: {type: deflection, deflection: 20 mm}\n");
}

const char* kSelfSensingScenario = R"(scenario: {name: example, duration: 10 s, seed: 7}
output: {rate: 20 Hz}
muscle:
  thermal_force: {form: reduced, kappa_P: 7.2e-3 N/J, kappa_c: 131.6e-3 1/s, ambient_temperature: 23 degC}
  mechanics: {k1: 10.8e-3 N/mm, k2: 2.7e-3 N/mm, damping: 4.3e-3 N*s/mm, force_offset: 106.9e-3 N}
  resistance: 10.18 ohm
  inductance: {lambda_l: 7.45 uH*mm, lambda_x: 28.8 mm, lambda_0: 1.148 uH}
drive:
  model: muscle_drive
  fidelity: averaged
  pwm_frequency: 20 Hz
  supply_voltage: 7 V
  series_resistance: 0.57 ohm
  measurement: {threshold_current: 14 mA, path_resistance: 0 ohm, timer_resolution: 1 ns, timing_noise: 3 ns, spike_probability: 0.05, spike_size: 50 ns}
  muscle: muscle
estimator:
  drive: drive
  inductance: {lambda_l: 2.81 us*mm, lambda_x: 28.8 mm, lambda_0: 0.433 us}
  filters: {moving_average: 2, median: 15, low_pass_cutoff: 0.111 Hz}
  thermal: {kappa_P: 7.2e-3 N/J, kappa_c: 131.6e-3 1/s, initial_thermal_force: 0 N}
  mechanics: {k1: 10.8e-3 N/mm, k2: 2.7e-3 N/mm, damping: 4.3e-3 N*s/mm, force_offset: 106.9e-3 N}
  calibration: {deflection_offset: 0 mm, force_offset: 0 mN}
controller:
  estimator: estimator
  target: force
  reference: 0.4 N
  gains: {proportional: 540 W/N, integral_time: 1 s, derivative_time: 0 s}
  power_limits: [0.10 W, 3.12 W]
  anti_windup: true
  derivative_on: error
  initial_power: 1 W
load: {type: deflection, deflection: 20 mm}
)";

// The self-sensing scenario with the loop closed outside (sim/stepper.h, tcpmsim.Simulator).
std::string external_controller_scenario() {
  std::string text = kSelfSensingScenario;
  text = text.substr(0, text.find("controller:\n"));
  return text +
         "controller: {type: external, drive: drive, power_limits: [0.10 W, 3.12 W], "
         "initial_power: 1 W, target: force, reference: 0.4 N}\nload: {type: deflection, "
         "deflection: 20 mm}\n";
}

}  // namespace

void follow_pwm(ScenarioBuilder& build, const std::string& sampled, const std::string& drive) {
  const std::string frequency = drive + ".pwm_frequency";
  build.system().derive(
      sampled + ".sample_period",
      [frequency](const Context& context) { return 1.0 / context.parameter(frequency); },
      "1 / " + frequency);
}

const MuscleDriveFacts& sensing_drive(const ConfigNode& node, const std::string& drive,
                                      const ScenarioBuilder& build) {
  const auto* facts = build.facts<MuscleDriveFacts>(drive);
  if (!facts) node.fail("self-sensing needs the Muscle Drive (drive.model: muscle_drive)");
  return *facts;
}

void check_takes_command(const MuscleDriveFacts& facts) {
  if (!facts.takes_command)
    facts.section.at("power").fail("the power comes from the controller; remove drive.power");
}

void register_controller_kinds(KindRegistry& kinds) {
  kinds.add_category({kDriveCategory, "drives", "model", "joule",
                      "what heats a muscle (muscle: <name>; the only muscle by default)", "", 30});
  kinds.add_category({kEstimatorCategory, "estimators", "", "",
                      "self-sensing of a muscle from its Muscle Drive's L* (drive: <name>; the "
                      "only drive by default)",
                      "", 40});
  kinds.add_category({kControllerCategory, "controllers", "type", "pid",
                      "closed-loop control: the built-in PID through an estimator (estimator: "
                      "<name>; the only one by default), commanding that estimator's drive, or "
                      "a controller outside tcpmsim (type: external) setting a drive's power "
                      "step by step",
                      "", 50});
  kinds.add({kDriveCategory,
             "joule",
             "Joule heating averaged over the PWM period: power, duty (7.2) or current",
             {{with_drive("drive: {mode: power, power: 1 W, muscle: muscle}\n"), "drive"},
              {with_drive("drive: {mode: duty, supply_voltage: 7 V, series_resistance: 0.57 ohm, "
                          "duty: 0.5}\n"),
               "drive"},
              {with_drive("drive: {mode: current, current: 0.3 A}\n"), "drive"}},
             InstanceBuilder(build_joule_drive)});
  kinds.add({kDriveCategory,
             "muscle_drive",
             "the thesis' Muscle Drive (7.2.1): PWM heating, averaged or switched, measuring the "
             "coil's decay time L*; power from a signal or from a controller",
             {{kSelfSensingScenario, "drive"}},
             InstanceBuilder(build_muscle_drive)});
  kinds.add({kEstimatorCategory,
             "self_sensing",
             "the L* filters, (7.4) and the force model (7.1), (7.5)-(7.6) in exact discrete time "
             "(7.2.2-7.2.3)",
             {{kSelfSensingScenario, "estimator"}},
             InstanceBuilder(build_estimator)});
  kinds.add({kControllerCategory,
             "pid",
             "PID on the estimated deflection or force with back-calculation anti-windup and "
             "saturation (7.7)-(7.9), sampled with the drive's PWM",
             {{kSelfSensingScenario, "controller"}},
             InstanceBuilder(build_controller)});
  kinds.add({kControllerCategory,
             "external",
             "the loop closed outside the system: a Python controller (tcpmsim.Simulator), an "
             "FMU's master or a C++ loop sets the drive's power each step, within power_limits, "
             "where the PID would act; it reports the task's reference (target, reference: "
             "optional, both or neither) as output reference",
             {{external_controller_scenario(), "controller"}},
             InstanceBuilder(build_external_controller)});
  register_joint_angle_controller(kinds);
  register_fan_controller(kinds);
}

}  // namespace tcpmsim
