#include "models/load_kinds.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "models/bundle/bundle_kind.h"
#include "models/hanging_mass.h"
#include "models/imposed_load.h"
#include "models/joint_load.h"
#include "models/muscle.h"
#include "models/sensor.h"

namespace tcpmsim {

namespace {

// The muscles a load holds, with what they published (a copy: rules made here outlive the
// builder).
struct Held {
  std::string name;
  MuscleFacts facts;
};

// The keys every load that holds muscles takes; each kind declares its own besides (a key of
// another kind is then no suggestion here).
std::vector<Held> held_muscles(const ConfigNode& node, ScenarioBuilder& build) {
  node.declare({"type", "muscle", "muscles", "bundle"});
  std::vector<Held> held;
  if (const auto bundle = node.find("bundle")) {
    for (const char* other : {"muscle", "muscles"}) {
      if (node.has(other))
        node.at(other).fail("give either 'bundle' or '" + std::string(other) + "', not both");
    }
    const auto& instance = build.linked(node, "bundle", kBundleCategory);
    for (const auto& member : build.facts<BundleFacts>(instance.name)->members)
      held.push_back({member, *build.facts<MuscleFacts>(member)});
    return held;
  }
  for (const auto* muscle : build.linked_all(node, "muscle", "muscles", kMuscleCategory))
    held.push_back({muscle->name, *build.facts<MuscleFacts>(muscle->name)});
  return held;
}

// (6.3) is singular at x = -lambda_x: the imposed deflection must stay above it, when read and
// in every run whose parameters move either.
void check_deflection_range(const ConfigNode& node, const Signal& deflection, const Held& muscle,
                            const std::string& load, ScenarioBuilder& build) {
  if (!muscle.facts.has_inductance) return;  // no inductance law, no singularity
  const double duration = build.settings().duration;
  const double lowest = deflection.range(0.0, duration).first;
  const double singular = -muscle.facts.lambda_x;
  if (!(lowest > singular)) {
    node.fail("the deflection reaches " + std::to_string(lowest) + " m, at or below -lambda_x = " +
              std::to_string(singular) + " m where the inductance law (6.3) is singular");
  }
  const std::string lambda_x = muscle.name + ".inductance.lambda_x";
  build.system().constrain([load, lambda_x, duration](const Context& context) -> std::string {
    const auto slot = context.system().signal_slot(load, "deflection");
    const double low = context.signal(*slot).range(0.0, duration).first;
    if (low > -context.parameter(lambda_x)) return {};
    return load + ".deflection: reaches " + std::to_string(low) + " m, at or below -" + lambda_x;
  });
}

void build_imposed_deflection(const ConfigNode& node, const std::string& name,
                              ScenarioBuilder& build) {
  node.declare({"deflection", "load_cell_resolution"});
  const auto muscles = held_muscles(node, build);
  SystemBuilder& system = build.system();
  const ConfigNode signal_node = node.at("deflection");
  auto signal = build.signal(signal_node, "m");
  for (const auto& muscle : muscles)
    check_deflection_range(signal_node, *signal, muscle, name, build);
  system.add(
      std::make_unique<ImposedLoad>(name, ImposedLoad::Quantity::deflection, std::move(signal)));
  auto& cell = system.add(Sensor::from_config(name, "force", "N", node, "load_cell_resolution"));
  for (const auto& muscle : muscles) {
    system.connect(muscle.name + ".deflection", name + ".deflection");
    system.connect(cell, "measured", muscle.name + ".force");
  }
}

void build_imposed_force(const ConfigNode& node, const std::string& name, ScenarioBuilder& build) {
  node.declare({"force", "position_resolution"});
  const auto muscles = held_muscles(node, build);
  if (muscles.size() > 1) {
    node.fail(
        "an imposed force holds one muscle: several in parallel need a common plate that "
        "shares the force between them");
  }
  SystemBuilder& system = build.system();
  system.add(std::make_unique<ImposedLoad>(name, ImposedLoad::Quantity::force,
                                           build.signal(node.at("force"), "N")));
  auto& encoder =
      system.add(Sensor::from_config(name, "deflection", "m", node, "position_resolution"));
  system.connect(muscles.front().name + ".force", name + ".force");
  system.connect(encoder, "measured", muscles.front().name + ".deflection");
}

// The deflection at which `weight` hangs still from muscles at rest: the static balance of (7.5)
// with relaxed dashpots, m g = sum (k1 x + F_T(0) + phi_0), and the rest forces of their
// attached terms (a parallel spring, a knee). Without such terms it is linear; with them the
// balance is bracketed from the linear one and bisected to the last bit (the muscles' rest
// force rises with the deflection). Throws std::domain_error if no deflection within 10 m
// balances the weight.
double static_balance(double weight, const std::vector<RestingMuscle>& muscles) {
  double net = weight, stiffness = 0.0;
  bool attached = false;
  for (const auto& muscle : muscles) {
    net = net - muscle.thermal_force - muscle.mechanics.force_offset;
    stiffness += muscle.mechanics.k1;
    attached = attached || !muscle.attached.empty();
  }
  const double linear = net / stiffness;
  if (!attached) return linear;
  const auto excess = [&](double deflection) {
    double force = -weight;
    for (const auto& muscle : muscles) force += muscle.force(deflection);
    return force;
  };
  double low = linear, high = linear;
  for (double step = std::max(1e-3, std::abs(linear)); excess(low) > 0.0 || excess(high) < 0.0;
       step *= 2.0) {
    if (step > 10.0)
      throw std::domain_error(
          "no deflection within 10 m balances the weight with the muscles' "
          "attached terms at rest");
    if (excess(low) > 0.0) low -= step;
    if (excess(high) < 0.0) high += step;
  }
  for (int i = 0; i < 200; ++i) {
    const double middle = 0.5 * (low + high);
    if (middle <= low || middle >= high) break;
    (excess(middle) < 0.0 ? low : high) = middle;
  }
  return 0.5 * (low + high);
}

void build_hanging_mass(const ConfigNode& node, const std::string& name, ScenarioBuilder& build) {
  node.declare({"mass", "gravity", "damping", "initial_deflection", "initial_velocity",
                "load_cell_resolution"});
  const auto muscles = held_muscles(node, build);
  std::vector<RestingMuscle> as_built;
  for (const auto& muscle : muscles) as_built.push_back(muscle.facts.resting);
  const auto equilibrium = [&as_built, &node](double weight) {
    try {
      return static_balance(weight, as_built);
    } catch (const std::domain_error& error) {
      node.at("initial_deflection").fail(error.what());
    }
  };
  SystemBuilder& system = build.system();
  auto& mass = system.add(HangingMass::from_config(name, node, equilibrium));
  if (const ConfigNode initial = node.at("initial_deflection"); initial.is_word("equilibrium")) {
    system.derive(
        name + ".initial_deflection",
        [muscles, hanging = &mass](const Context& context) {
          std::vector<RestingMuscle> resting;
          for (const auto& muscle : muscles) resting.push_back(muscle.facts.resting_in(context));
          const HangingMassParameters p = hanging->parameters_in(context);
          return static_balance(p.mass * p.gravity, resting);
        },
        "the static balance m g = sum of k1 x + F_T + phi_0 and the attached terms at rest");
  }
  auto& cell = system.add(Sensor::from_config(name, "force", "N", node, "load_cell_resolution"));
  for (const auto& muscle : muscles) {
    system.connect(muscle.name + ".deflection", name + ".deflection");
    system.connect(mass, "force", muscle.name + ".force");
    system.connect(cell, "measured", muscle.name + ".force");
  }
}

std::string example(const std::string& load) {
  return example_muscle_scenario("", "drive: {mode: power, power: 1 W}\n" + load);
}

}  // namespace

void register_load_kinds(KindRegistry& kinds) {
  kinds.add_category({kLoadCategory, "loads", "type", "",
                      "what holds the muscles (muscle: <name>, muscles: [names], or a bundle's: "
                      "bundle: <name>; the only muscle by default)",
                      "", 60});
  kinds.add({kLoadCategory,
             "deflection",
             "a testing machine in position mode: imposes the deflection on its muscles and "
             "measures their summed force (load cell)",
             {{example("load: {type: deflection, deflection: 20 mm, load_cell_resolution: 0.5 "
                       "mN, muscle: muscle}\n"),
               "load"}},
             InstanceBuilder(build_imposed_deflection)});
  kinds.add(
      {kLoadCategory,
       "force",
       "a testing machine in force mode: imposes the force on one muscle and measures its "
       "deflection (encoder)",
       {{example("load: {type: force, force: 0.4 N, position_resolution: 0.02 mm}\n"), "load"}},
       InstanceBuilder(build_imposed_force)});
  kinds.add(
      {kLoadCategory,
       "hanging_mass",
       "a mass hanging from its muscles under gravity, m x'' = m g - F - b x'; "
       "initial_deflection may be `equilibrium`",
       {{example("load: {type: hanging_mass, mass: 35 g, gravity: 9.81 m/s^2, damping: 0.05 "
                 "N*s/m, initial_deflection: equilibrium, initial_velocity: 0 m/s, "
                 "load_cell_resolution: 0.5 mN}\n"),
         "load"},
        {example("load: {type: hanging_mass, mass: 35 g, initial_deflection: 20 mm}\n"), "load"}},
       InstanceBuilder(build_hanging_mass)});
  register_joint_load(kinds);
}

}  // namespace tcpmsim
