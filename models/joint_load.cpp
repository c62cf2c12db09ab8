#include "models/joint_load.h"

#include <algorithm>

#include "models/antagonistic_joint.h"
#include "models/muscle.h"
#include "models/sensor.h"
#include "sim/scenario_builder.h"

namespace tcpmsim {

namespace {

// A held muscle's relaxed force at the cable's deflection x, 0 when slack: max(0, k1 x + F_T +
// phi_0) ((7.5) with the dashpot relaxed).
struct RelaxedMuscle {
  double k1, thermal_force, force_offset;
  double operator()(double deflection) const {
    return std::max(0.0, k1 * deflection + thermal_force + force_offset);
  }
};

RelaxedMuscle relaxed_as_built(const MuscleFacts& facts) {
  return {facts.mechanics.k1, facts.initial_thermal_force, facts.mechanics.force_offset};
}

RelaxedMuscle relaxed_in(const Context& context, const std::string& muscle,
                         const MuscleFacts& facts) {
  return {context.parameter(muscle + ".mechanics.k1"), facts.initial_thermal_force_in(context),
          context.parameter(muscle + ".mechanics.force_offset")};
}

// The joint's parameters as a run has them (the keys from_config binds).
AntagonisticJointParameters joint_in(const Context& context, const std::string& joint,
                                     bool has_spring) {
  AntagonisticJointParameters p;
  p.radius = context.parameter(joint + ".radius");
  p.left_pre_deflection = context.parameter(joint + ".pre_deflection.left");
  p.right_pre_deflection = context.parameter(joint + ".pre_deflection.right");
  if (has_spring) {
    p.spring_stiffness = context.parameter(joint + ".spring.stiffness");
    p.spring_rest_angle = context.parameter(joint + ".spring.rest_angle");
  }
  return p;
}

void build_joint(const ConfigNode& node, const std::string& name, ScenarioBuilder& build) {
  node.declare({"type", "left", "right", "radius", "inertia", "damping", "spring", "pre_deflection",
                "load_torque", "initial_angle", "initial_velocity", "encoder_resolution"});
  const auto& left = build.linked(node, "left", kMuscleCategory);
  const auto& right = build.linked(node, "right", kMuscleCategory);
  if (left.name == right.name) node.at("right").fail("expected a muscle other than the left one");
  const MuscleFacts left_facts = *build.facts<MuscleFacts>(left.name);
  const MuscleFacts right_facts = *build.facts<MuscleFacts>(right.name);
  if (const auto initial = node.find("initial_angle");
      initial && initial->is_scalar() && initial->as_text() == "equilibrium") {
    for (const auto* held : {&left, &right}) {
      if (build.facts<MuscleFacts>(held->name)->rest_force_attached) {
        initial->fail("the equilibrium is found from k1, F_T and phi_0 alone, but " + held->name +
                      " has an effect that carries force at rest; give the angle");
      }
    }
  }
  const auto equilibrium = [&](const AntagonisticJointParameters& p, double load_torque) {
    return joint::balance_angle(p, load_torque, relaxed_as_built(left_facts),
                                relaxed_as_built(right_facts));
  };
  bool at_equilibrium = false;
  SystemBuilder& system = build.system();
  auto& joint = system.add(
      AntagonisticJoint::from_config(name, node, build.signals(), equilibrium, &at_equilibrium));
  if (at_equilibrium) {
    const bool has_spring = node.has("spring");
    const bool has_torque = joint.has_load_torque();
    system.derive(
        name + ".initial_angle",
        [=, left = left.name, right = right.name](const Context& context) {
          const double torque =
              has_torque
                  ? context.signal(*context.system().signal_slot(name, "load_torque")).value(0.0)
                  : 0.0;
          return joint::balance_angle(joint_in(context, name, has_spring), torque,
                                      relaxed_in(context, left, left_facts),
                                      relaxed_in(context, right, right_facts));
        },
        "the static balance r (F_right - F_left) - k_s (theta - theta_s) + tau(0) = 0 with "
        "relaxed muscles");
  }
  system.connect(left.name + ".cable_deflection", name + ".left_deflection");
  system.connect(right.name + ".cable_deflection", name + ".right_deflection");
  system.connect(joint, "left_force", left.name + ".force");
  system.connect(joint, "right_force", right.name + ".force");

  auto& stiffness = system.add(std::make_unique<JointStiffness>(name));
  system.connect(stiffness, "radius", name + ".radius");
  system.connect(stiffness, "spring_stiffness", name + ".spring_stiffness");
  system.connect(stiffness, "left_stiffness", left.name + ".stiffness");
  system.connect(stiffness, "right_stiffness", right.name + ".stiffness");
  system.connect(stiffness, "left_rest_stiffness", left.name + ".rest_stiffness");
  system.connect(stiffness, "right_rest_stiffness", right.name + ".rest_stiffness");

  auto& encoder =
      system.add(Sensor::from_config(name, "measured_angle", "rad", node, "encoder_resolution"));
  system.connect(encoder, "measured", name + ".angle");
}

}  // namespace

void register_joint_load(KindRegistry& kinds, const char* load_category) {
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
  kinds.add({load_category,
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
