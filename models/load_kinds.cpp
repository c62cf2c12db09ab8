#include "models/load_kinds.h"

#include <string>
#include <vector>

#include "models/hanging_mass.h"
#include "models/imposed_load.h"
#include "models/joint_load.h"
#include "models/muscle.h"
#include "models/sensor.h"

namespace tcpmsim {

namespace {

inline constexpr const char* kLoadCategory = "load";

// The muscles a load holds, with what they published (a copy: rules made here outlive the
// builder).
struct Held {
  std::string name;
  MuscleFacts facts;
};

std::vector<Held> held_muscles(const ConfigNode& node, ScenarioBuilder& build) {
  node.declare({"type", "muscle", "muscles", "deflection", "force", "mass", "gravity", "damping",
                "initial_deflection", "initial_velocity", "load_cell_resolution",
                "position_resolution"});
  std::vector<Held> held;
  for (const auto* muscle : build.linked_all(node, "muscle", "muscles", kMuscleCategory))
    held.push_back({muscle->name, *build.facts<MuscleFacts>(muscle->name)});
  return held;
}

// (6.3) is singular at x = -lambda_x: the imposed deflection must stay above it, when read and
// in every run whose parameters move either.
void check_deflection_range(const ConfigNode& node, const Signal& deflection, const Held& muscle,
                            const std::string& load, ScenarioBuilder& build) {
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

// What a held muscle contributes to the static balance at the start.
struct RestTerms {
  double thermal_force;  // F_T(0)
  double force_offset;   // phi_0
  double k1;
};

// The deflection at which `weight` hangs still from muscles at rest: the static balance of (7.5)
// with relaxed dashpots, m g = sum (k1 x + F_T(0) + phi_0). Attached terms must carry no force
// at rest (a Maxwell arm carries none); a muscle with one that does is refused by the caller.
template <typename Terms>
double static_balance(double weight, const std::vector<Held>& muscles, Terms terms) {
  double net = weight, stiffness = 0.0;
  for (const auto& muscle : muscles) {
    const RestTerms rest = terms(muscle);
    net = net - rest.thermal_force - rest.force_offset;
    stiffness += rest.k1;
  }
  return net / stiffness;
}

void build_hanging_mass(const ConfigNode& node, const std::string& name, ScenarioBuilder& build) {
  const auto muscles = held_muscles(node, build);
  if (const auto initial = node.find("initial_deflection");
      initial && initial->is_scalar() && initial->as_text() == "equilibrium") {
    for (const auto& muscle : muscles) {
      if (muscle.facts.rest_force_attached) {
        initial->fail("the equilibrium is found from k1, F_T and phi_0 alone, but " + muscle.name +
                      " has an effect that carries force at rest; give the deflection");
      }
    }
  }
  const auto equilibrium = [muscles](double weight) {
    return static_balance(weight, muscles, [](const Held& muscle) {
      return RestTerms{muscle.facts.initial_thermal_force, muscle.facts.mechanics.force_offset,
                       muscle.facts.mechanics.k1};
    });
  };
  bool at_equilibrium = false;
  SystemBuilder& system = build.system();
  auto& mass = system.add(HangingMass::from_config(name, node, equilibrium, &at_equilibrium));
  if (at_equilibrium) {
    system.derive(
        name + ".initial_deflection",
        [muscles, name](const Context& context) {
          return static_balance(
              context.parameter(name + ".mass") * context.parameter(name + ".gravity"), muscles,
              [&context](const Held& muscle) {
                return RestTerms{muscle.facts.initial_thermal_force_in(context),
                                 context.parameter(muscle.name + ".mechanics.force_offset"),
                                 context.parameter(muscle.name + ".mechanics.k1")};
              });
        },
        "the static balance m g = sum of k1 x + F_T + phi_0");
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
                      "what holds the muscles (muscle: <name>, or muscles: [names]; the only "
                      "muscle by default)",
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
  register_joint_load(kinds, kLoadCategory);
}

}  // namespace tcpmsim
