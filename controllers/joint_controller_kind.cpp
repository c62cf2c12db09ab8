#include "controllers/joint_controller_kind.h"

#include <string_view>
#include <vector>

#include "controllers/controller_facts.h"
#include "controllers/joint_angle_controller.h"
#include "models/joint_load.h"
#include "models/load_kinds.h"
#include "models/muscle.h"

namespace tcpmsim {

namespace {

// The instances of `category` whose published Facts match.
template <typename Facts, typename Match>
std::vector<std::string> instances_where(const ScenarioBuilder& build, std::string_view category,
                                         Match match) {
  std::vector<std::string> found;
  for (const auto* instance : build.instances(category)) {
    const auto* facts = build.facts<Facts>(instance->name);
    if (facts && match(*facts)) found.push_back(instance->name);
  }
  return found;
}

// The one Muscle Drive that heats `muscle`, or a located error.
std::string drive_of(const ConfigNode& node, const std::string& muscle,
                     const ScenarioBuilder& build) {
  const auto found = instances_where<MuscleDriveFacts>(
      build, kDriveCategory, [&](const MuscleDriveFacts& drive) { return drive.muscle == muscle; });
  if (found.size() != 1) {
    node.fail(
        "joint-angle control commands the Muscle Drive (drive model: muscle_drive) of each "
        "muscle; " +
        muscle + " has " + std::to_string(found.size()));
  }
  return found.front();
}

// The one estimator that reads `drive`, or a located error.
std::string estimator_of(const ConfigNode& node, const std::string& drive,
                         const ScenarioBuilder& build) {
  const auto found = instances_where<EstimatorFacts>(
      build, kEstimatorCategory,
      [&](const EstimatorFacts& estimator) { return estimator.drive == drive; });
  if (found.size() != 1) {
    node.at("feedback")
        .fail("self-sensing reads one estimator per muscle; the drive " + drive + " has " +
              std::to_string(found.size()));
  }
  return found.front();
}

void build_joint_angle(const ConfigNode& node, const std::string& name, ScenarioBuilder& build) {
  node.declare({"type", "joint", "feedback", "reference", "co_contraction", "gains", "power_limits",
                "anti_windup", "derivative_on", "model"});
  const auto& joint = build.linked(node, "joint", kLoadCategory);
  if (joint.kind->name != kJointKind)
    node.fail("expected a joint to control; " + joint.name + " is a load of type " +
              joint.kind->name);
  const std::string left = build.linked(joint.node, "left", kMuscleCategory).name;
  const std::string right = build.linked(joint.node, "right", kMuscleCategory).name;
  const bool self_sensing = node.choice("feedback", {"encoder", "self_sensing"}) == "self_sensing";
  const std::string left_drive = drive_of(node, left, build);
  const std::string right_drive = drive_of(node, right, build);
  // drive_of finds only Muscle Drives, which publish these.
  const MuscleDriveFacts& left_facts = *build.facts<MuscleDriveFacts>(left_drive);
  const MuscleDriveFacts& right_facts = *build.facts<MuscleDriveFacts>(right_drive);
  check_takes_command(left_facts);
  check_takes_command(right_facts);
  if (left_facts.period != right_facts.period) {
    // Reported at the setting that differs: the right drive's frequency, or the left's when the
    // right one takes the default.
    const auto at =
        right_facts.section.find("pwm_frequency")  ? right_facts.section.at("pwm_frequency")
        : left_facts.section.find("pwm_frequency") ? left_facts.section.at("pwm_frequency")
                                                   : node;
    at.fail("the drives " + left_drive + " and " + right_drive +
            " run at different PWM frequencies; the joint-angle controller " + name +
            " samples both with one period");
  }
  SystemBuilder& system = build.system();
  system.constrain([left_drive, right_drive](const Context& context) -> std::string {
    if (context.parameter(left_drive + ".pwm_frequency") ==
        context.parameter(right_drive + ".pwm_frequency"))
      return {};
    return left_drive + ".pwm_frequency and " + right_drive +
           ".pwm_frequency: a joint-angle controller needs them equal";
  });
  auto& controller = system.add(JointAngleController::from_config(name, node, left_facts.period,
                                                                  self_sensing, build.signals()));
  system.connect(left_drive + ".power_command", name + ".left_power_command");
  system.connect(right_drive + ".power_command", name + ".right_power_command");
  if (self_sensing) {
    system.connect(controller, "left_deflection",
                   estimator_of(node, left_drive, build) + ".deflection");
    system.connect(controller, "right_deflection",
                   estimator_of(node, right_drive, build) + ".deflection");
  } else {
    system.connect(controller, "angle", joint.name + ".measured_angle");
  }
  follow_pwm(build, name, left_drive);
}

std::string joint_example(const std::string& feedback) {
  const std::string drive =
      "    model: muscle_drive\n    fidelity: averaged\n    supply_voltage: 7 V\n"
      "    series_resistance: 0.57 ohm\n    measurement: {threshold_current: 14 mA}\n";
  const std::string estimator =
      "    inductance: {lambda_l: 2.81 us*mm, lambda_x: 28.8 mm, lambda_0: 0.433 us}\n"
      "    thermal: {kappa_P: 7.2e-3 N/J, kappa_c: 131.6e-3 1/s}\n"
      "    mechanics: {k1: 10.8e-3 N/mm, k2: 2.7e-3 N/mm, damping: 4.3e-3 N*s/mm, force_offset: "
      "106.9e-3 N}\n";
  return R"(scenario: {name: example, duration: 10 s, seed: 7}
output: {rate: 20 Hz}
muscles:
  left: &muscle
    thermal_force: {form: reduced, kappa_P: 7.2e-3 N/J, kappa_c: 131.6e-3 1/s, ambient_temperature: 23 degC}
    mechanics: {k1: 10.8e-3 N/mm, k2: 2.7e-3 N/mm, damping: 4.3e-3 N*s/mm, force_offset: 106.9e-3 N}
    resistance: 10.18 ohm
    inductance: {lambda_l: 7.45 uH*mm, lambda_x: 28.8 mm, lambda_0: 1.148 uH}
  right: *muscle
drives:
  left_drive:
    muscle: left
)" + drive +
         "  right_drive:\n    muscle: right\n" + drive +
         "estimators:\n  left_estimator:\n    drive: left_drive\n" + estimator +
         "  right_estimator:\n    drive: right_drive\n" + estimator + R"(load:
  type: joint
  left: left
  right: right
  radius: 10 mm
  inertia: 1e-5 kg*m^2
  damping: 1e-4 N*m*s/rad
  pre_deflection: {left: 20 mm, right: 20 mm}
  encoder_resolution: 0.001 rad
controller:
  type: joint_angle
  joint: load
  reference: {type: steps, initial: 0 rad, times: [2 s], values: [0.2 rad]}
  co_contraction: 1.6 W
  gains: {proportional: 21.6 W/rad, integral_time: 2.5 s, derivative_time: 0.625 s}
  power_limits: [0.10 W, 3.12 W]
  anti_windup: true
  derivative_on: error
  )" + feedback;
}

}  // namespace

void register_joint_angle_controller(KindRegistry& kinds) {
  kinds.add({kControllerCategory,
             "joint_angle",
             "the angle of an antagonistic joint (a load of type joint) with a co-contraction "
             "level: PID (7.7)-(7.9) on the differential power, push-pull around the level, "
             "through the joint's encoder or the two muscles' self-sensed deflections",
             {{joint_example("feedback: self_sensing\n  model: {radius: 10 mm, pre_deflection: "
                             "{left: 20 mm, right: 20 mm}}\n"),
               "controller"},
              {joint_example("feedback: encoder\n"), "controller"}},
             InstanceBuilder(build_joint_angle)});
}

}  // namespace tcpmsim
