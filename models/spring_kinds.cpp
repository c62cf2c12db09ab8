#include "models/spring_kinds.h"

#include "models/coil_spring_chain.h"
#include "models/coil_spring_inductance.h"
#include "sim/context.h"
#include "sim/scenario_builder.h"

namespace tcpmsim {

namespace {

void build_spring(const ConfigNode& spring, const std::string& name, ScenarioBuilder& build) {
  spring.declare({"windings", "rest_length", "mass", "stiffness", "damping_ratio",
                  "initial_velocity", "first_end", "second_end", "inductance"});
  SystemBuilder& system = build.system();
  auto& chain = system.add(CoilSpringChain::from_config(name, spring, build.signals()));
  const auto inductance = spring.find("inductance");
  if (!inductance) return;
  const double initial_length = chain.end_position(1, 0.0) - chain.end_position(0, 0.0);
  const bool preload_given = inductance->has("preload_length");
  auto& sensor = system.add(
      CoilSpringInductance::from_config(name, *inductance, chain.defaults(), initial_length, name));
  for (const auto& input : sensor.inputs())
    system.connect(sensor, input.name, name + "." + input.name);
  if (!preload_given) {
    // The static length between the ends at the start, in every run.
    system.derive(
        name + ".inductance.preload_length",
        [name](const Context& context) {
          const auto& system = context.system();
          return context.signal(*system.signal_slot(name, "second_end")).value(0.0) -
                 context.signal(*system.signal_slot(name, "first_end")).value(0.0);
        },
        "second_end - first_end at the start");
  }
}

}  // namespace

void register_spring_kinds(KindRegistry& kinds) {
  kinds.add_category({"spring", "springs", "", "",
                      "a metal coil spring whose own coil is the sensor (thesis ch. 2-4)", "", 10});
  kinds.add({"spring",
             "coil_spring",
             "N lumped windings between imposed ends (4.4)-(4.7); with `inductance`, Maxwell's "
             "sum over the actual gaps (4.11) and the force sensed through (4.13)",
             {{R"(scenario: {name: example, duration: 0.01 s}
output: {rate: 10 kHz}
solver: {method: adams, rtol: 1.0e-8}
spring:
  windings: 25
  rest_length: 80 mm
  mass: 80 g
  stiffness: 9100 N/m
  damping_ratio: 0.01
  first_end: 0 mm
  second_end: {type: sine, offset: 120 mm, amplitude: 1 mm, frequency: 100 Hz}
  initial_velocity: {profile: linear, value: 0.1 m/s}
  inductance: {coil_radius: 10 mm, wire_diameter: 3 mm, operating_range: [110 mm, 130 mm], preload_length: 120 mm}
)",
               "spring"}},
             InstanceBuilder(build_spring)});
}

}  // namespace tcpmsim
