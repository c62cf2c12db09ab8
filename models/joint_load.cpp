#include "models/joint_load.h"

#include <algorithm>

#include "models/antagonistic_joint.h"
#include "models/load_kinds.h"
#include "models/muscle.h"
#include "models/sensor.h"
#include "sim/scenario_builder.h"

namespace tcpmsim {

namespace {

// A muscle at rest pulling through a cable: its relaxed force (7.5), 0 when slack.
std::function<double(double)> cable_force(const RestingMuscle& muscle) {
  return [muscle](double deflection) { return std::max(0.0, muscle.force(deflection)); };
}

void build_joint(const ConfigNode& node, const std::string& name, ScenarioBuilder& build) {
  node.declare({"type", "left", "right", "radius", "inertia", "damping", "spring", "pre_deflection",
                "load_torque", "initial_angle", "initial_velocity", "encoder_resolution"});
  const auto& left = build.linked(node, "left", kMuscleCategory);
  const auto& right = build.linked(node, "right", kMuscleCategory);
  if (left.name == right.name) node.at("right").fail("expected a muscle other than the left one");
  const MuscleFacts& left_facts = *build.facts<MuscleFacts>(left.name);
  const MuscleFacts& right_facts = *build.facts<MuscleFacts>(right.name);
  const auto initial = node.find("initial_angle");
  const bool at_equilibrium = initial && initial->is_word("equilibrium");
  if (at_equilibrium) {
    check_resting_balance(*initial, left.name, left_facts, "the angle");
    check_resting_balance(*initial, right.name, right_facts, "the angle");
  }
  const auto equilibrium = [&](const AntagonisticJointParameters& p, double load_torque) {
    return joint::balance_angle(p, load_torque, cable_force(left_facts.resting),
                                cable_force(right_facts.resting));
  };
  SystemBuilder& system = build.system();
  auto& joint =
      system.add(AntagonisticJoint::from_config(name, node, build.signals(), equilibrium));
  if (at_equilibrium) {
    system.derive(
        name + ".initial_angle",
        [pulley = &joint, left = left_facts.resting_in,
         right = right_facts.resting_in](const Context& context) {
          return joint::balance_angle(pulley->parameters_in(context),
                                      pulley->load_torque_at_start(context),
                                      cable_force(left(context)), cable_force(right(context)));
        },
        "the static balance r (F_right - F_left) - k_s (theta - theta_s) + tau(0) = 0 with "
        "relaxed muscles");
  }
  for (const auto& [side, muscle] :
       {std::pair{"left", left.name}, std::pair{"right", right.name}}) {
    const std::string prefix = std::string(side) + "_";
    system.connect(muscle + ".cable_deflection", name + "." + prefix + "deflection");
    system.connect(joint, prefix + "force", muscle + ".force");
    system.connect(joint, prefix + "stiffness", muscle + ".stiffness");
    system.connect(joint, prefix + "rest_stiffness", muscle + ".rest_stiffness");
  }
  auto& encoder =
      system.add(Sensor::from_config(name, "measured_angle", "rad", node, "encoder_resolution"));
  system.connect(encoder, "measured", name + ".angle");
}

}  // namespace

void register_joint_load(KindRegistry& kinds) {
  const std::string pair = R"(scenario: {name: example, duration: 10 s, seed: 1}
output: {rate: 10 Hz}
muscles:
  left: &muscle
    thermal_force: {form: reduced, kappa_P: 7.2e-3 N/J, kappa_c: 131.6e-3 1/s, ambient_temperature: 23 degC, force_per_kelvin: 4 mN/K}
    mechanics: {k1: 10.8e-3 N/mm, k2: 2.7e-3 N/mm, damping: 4.3e-3 N*s/mm, force_offset: 106.9e-3 N}
    resistance: 10.18 ohm
    inductance: {quantity: measure, lambda_l: 2.81 mm, lambda_x: 28.8 mm, lambda_0: 0.433}
  right: *muscle
drives:
  d1: {muscle: left, mode: power, power: 0.5 W}
  d2: {muscle: right, mode: power, power: {type: steps, initial: 0.5 W, times: [2 s], values: [2 W]}}
)";
  kinds.add({kLoadCategory,
             kJointKind,
             "an antagonistic pair on a pulley: J w' = r (F_right - F_left) - b w - k_s (theta - "
             "theta_s) + tau; the muscles pull through cables and go slack rather than push",
             {{pair + R"(load:
  type: joint
  left: left
  right: right
  radius: 10 mm
  inertia: 1e-5 kg*m^2
  damping: 1e-4 N*m*s/rad
  spring: {stiffness: 1e-4 N*m/rad, rest_angle: 0 rad}
  pre_deflection: {left: 20 mm, right: 20 mm}
  load_torque: {type: steps, initial: 0 N*m, times: [5 s], values: [1e-4 N*m]}
  initial_angle: equilibrium
  initial_velocity: 0 rad/s
  encoder_resolution: 0.001 rad
)",
               "load"},
              {pair + R"(load:
  type: joint
  left: left
  right: right
  radius: 10 mm
  inertia: 1e-5 kg*m^2
  pre_deflection: {left: 20 mm, right: 5 mm}
  initial_angle: 0.1 rad
)",
               "load"}},
             InstanceBuilder(build_joint)});
}

}  // namespace tcpmsim
