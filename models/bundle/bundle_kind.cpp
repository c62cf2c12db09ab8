#include "models/bundle/bundle_kind.h"

#include <iomanip>
#include <optional>
#include <sstream>

#include "models/bundle/bundle_air.h"
#include "models/bundle/bundle_magnetics.h"
#include "models/bundle/bundle_supply.h"
#include "models/bundle/parameter_spread.h"
#include "models/laws/packing.h"
#include "models/muscle.h"
#include "models/typical_values.h"
#include "sim/scenario_builder.h"

namespace tcpmsim {

namespace {

// The drive and estimator categories are registered by the controllers; a bundle builds its
// members' drives and estimators by those names, through the registry.
constexpr const char* kDriveCategory = "drive";
constexpr const char* kEstimatorCategory = "estimator";

// The most members a bundle may have: building one takes about half a millisecond and 30 kB a
// member before it runs (10 000: a few seconds and 300 MB), and its run far more.
constexpr double kMaxMembers = 1e4;
constexpr const char* kMembersCost =
    "each member is a muscle with its own components: half a millisecond and 30 kB a member to "
    "build";

// "m0" ... "m9", "m00" ... "m18": as many digits as the largest index needs.
std::vector<std::string> member_ids(int count) {
  const int digits = std::max(1, static_cast<int>(std::to_string(count - 1).size()));
  std::vector<std::string> ids;
  for (int k = 0; k < count; ++k) {
    std::ostringstream id;
    id << 'm' << std::setw(digits) << std::setfill('0') << k;
    ids.push_back(id.str());
  }
  return ids;
}

BundleCrossSection read_cross_section(const ConfigNode& node, int count) {
  node.declare({"layout", "pitch"});
  const PackingLayout layout = node.choice("layout", {"hexagonal", "square"}) == "square"
                                   ? PackingLayout::square
                                   : PackingLayout::hexagonal;
  return packing::cross_section(
      layout, count, node.quantity("pitch", "m", typical::fibre_pitch(ValueCheck::positive())));
}

struct Bundle {
  std::string name;
  std::vector<std::string> members;  // instance names "b/m00"
  BundleCrossSection section;
};

// Member k's packed convection and its exchange with its neighbours and the fan.
void couple_heat(const Bundle& bundle, std::size_t k, const BundleAir& air,
                 const ParameterSpread& spread, SystemBuilder& system) {
  const std::string& member = bundle.members[k];
  const auto& neighbours = bundle.section.neighbours[k];
  const int coordination = bundle.section.coordination();
  auto& exchange = system.add(std::make_unique<PackedHeatExchange>(
      member + "/packing", air, static_cast<int>(neighbours.size()), coordination));
  system.connect(exchange, "temperature", member + ".temperature");
  for (const int other : neighbours) {
    if (!air.contact()) break;  // no conduction: the members stay thermally uncoupled
    system.connect(exchange, "neighbour_temperatures",
                   bundle.members[static_cast<std::size_t>(other)] + ".temperature");
  }
  system.connect(exchange, "ambient_temperature", member + ".ambient_temperature");
  system.connect(exchange, "fan_speed", bundle.name + "/air.fan_speed");
  system.connect(member + ".heat_loss", member + "/packing.to_neighbours");
  system.connect(member + ".heat_loss", member + "/packing.to_fan");
  const double spread_factor = spread.factor("thermal.conductance", k);
  const int count = static_cast<int>(neighbours.size());
  derive_scaled(
      system, member + ".thermal.conductance",
      [&air, count, coordination, spread_factor](const Context& context) {
        const double shielding = air.parameters_in(context).shielding;
        return packing::exposed_fraction(count, coordination, shielding) * spread_factor;
      },
      "the muscle section's conductance times the exposed fraction 1 - shielding * " +
          std::to_string(count) + "/" + std::to_string(coordination) +
          (spread.has("thermal.conductance") ? " and the member's spread factor" : ""));
}

// Each member's own drive and, if the section has one, its own estimator reading that drive.
void drive_members(const ConfigNode& node, const Bundle& bundle, ScenarioBuilder& build) {
  const ConfigNode drive = node.at("drive");
  if (drive.has("muscle"))
    drive.at("muscle").fail("each member's drive heats its own muscle; remove 'muscle'");
  const Kind& kind = build.kinds().select(kDriveCategory, drive);
  const auto estimator = node.find("estimator");
  if (estimator && estimator->has("drive"))
    estimator->at("drive").fail("each member's estimator reads its own drive; remove 'drive'");
  for (const auto& member : bundle.members) {
    build.build_member(kDriveCategory, member + "/drive", drive, kind, {{kMuscleCategory, member}});
    if (estimator) {
      build.build_member(kEstimatorCategory, member + "/estimator", *estimator,
                         build.kinds().select(kEstimatorCategory, *estimator),
                         {{kDriveCategory, member + "/drive"}});
    }
  }
}

void wire_members(const ConfigNode& node, const Bundle& bundle, ScenarioBuilder& build) {
  node.declare({"wiring", "drive", "estimator"});
  const std::string wiring = node.choice("wiring", {"individual", "series", "parallel"});
  SystemBuilder& system = build.system();
  if (wiring == "individual") {
    drive_members(node, bundle, build);
    return;
  }
  for (const char* key : {"drive", "estimator"}) {
    if (node.has(key))
      node.at(key).fail("one supply feeds a " + wiring + " bundle; '" + std::string(key) +
                        "' is for wiring: individual");
  }
  const BundleWiring circuit = wiring == "series" ? BundleWiring::series : BundleWiring::parallel;
  const std::string supply = bundle.name + "/supply";
  auto& source = system.add(BundleSupply::from_config(supply, node, circuit, build.signals()));
  for (const auto& member : bundle.members) {
    auto& wire = system.add(std::make_unique<MemberWire>(member + "/wire", circuit));
    system.connect(source, "resistance", member + ".resistance");
    system.connect(wire, "resistance", member + ".resistance");
    system.connect(wire, "bundle_voltage", supply + ".voltage");
    system.connect(wire, "bundle_current", supply + ".current");
    system.connect(member + ".power", member + "/wire.power");
  }
}

// Each member's coil couples to its touching neighbours' (magnetic: {coil: {...}}).
void couple_coils(const ConfigNode& magnetic, const Bundle& bundle, ScenarioBuilder& build) {
  if (build.facts<MuscleFacts>(bundle.members.front())->inductance_is_measure)
    magnetic.fail(
        "mutual inductances are in henries: give the muscles' inductance in henries, "
        "not as the measure L*");
  const auto mutual = NeighbourMutual::from_config(magnetic, bundle.section.pitch);
  SystemBuilder& system = build.system();
  for (std::size_t k = 0; k < bundle.members.size(); ++k) {
    const std::string& member = bundle.members[k];
    auto& term = system.add(std::make_unique<MemberMutual>(
        member + "/magnetic", mutual, static_cast<int>(bundle.section.neighbours[k].size())));
    system.connect(term, "deflection", member + ".deflection");
    system.connect(member + ".mutual_inductances", member + "/magnetic.mutual_inductance");
    build.publish(member + "/magnetic",
                  MemberCouplingFacts{static_cast<int>(bundle.section.neighbours[k].size()),
                                      bundle.section.pitch});
  }
}

// A fan with speed: controller exports its command as "<bundle>.fan_command", and the scenario
// must have a controller that drives it.
BundleAir::Fan expect_fan_command(const ConfigNode& node, const std::string& name,
                                  const BundleAir& air, ScenarioBuilder& build) {
  if (air.fan() != BundleAir::Fan::commanded) return air.fan();
  SystemBuilder& system = build.system();
  const std::string port = name + ".fan_command";
  system.export_input(port, air, "fan_command");
  const ConfigNode speed = node.at("thermal").at("fan").at("speed");
  build.after_building([&system, port, speed] {
    if (!system.is_connected(port))
      speed.fail(
          "no controller commands this fan: add one (type: fan, bundle: <name>) or give "
          "the speed as a signal");
  });
  return BundleAir::Fan::commanded;
}

void build_bundle(const ConfigNode& node, const std::string& name, ScenarioBuilder& build) {
  node.declare({"count", "packing", "muscle", "spread", "thermal", "electrical", "magnetic"});
  const int count =
      static_cast<int>(node.integer("count", ValueCheck::count(kMaxMembers, kMembersCost)));
  Bundle bundle{name, {}, read_cross_section(node.at("packing"), count)};
  const auto ids = member_ids(count);
  for (const auto& id : ids) bundle.members.push_back(name + "/" + id);

  SystemBuilder& system = build.system();
  const auto& air =
      system.add(BundleAir::from_config(name + "/air", node.at("thermal"), build.signals()));
  const ConfigNode muscle = node.at("muscle");
  const Kind& kind = build.kinds().select(kMuscleCategory, muscle);
  std::optional<ParameterSpread> spread;
  for (std::size_t k = 0; k < bundle.members.size(); ++k) {
    const std::string& member = bundle.members[k];
    build.build_member(kMuscleCategory, member, muscle, kind, {});
    if (!build.facts<MuscleFacts>(member)->thermal.heat_balance) {
      muscle.at("thermal_force")
          .fail("a bundle's muscles exchange heat: give them a thermal node (form: physical)");
    }
    if (!spread) {
      spread = ParameterSpread::from_config(node.find("spread"), name, ids.size(), member,
                                            build.settings().seed, system);
    }
    couple_heat(bundle, k, air, *spread, system);
    spread->apply(k, member, system, {"thermal.conductance"});
  }
  if (const auto magnetic = node.find("magnetic")) couple_coils(*magnetic, bundle, build);
  wire_members(node.at("electrical"), bundle, build);
  MemberSet set{name, ids, {}};
  std::vector<double> x, y, neighbours;
  for (std::size_t k = 0; k < bundle.members.size(); ++k) {
    x.push_back(bundle.section.centres[k][0]);
    y.push_back(bundle.section.centres[k][1]);
    neighbours.push_back(static_cast<double>(bundle.section.neighbours[k].size()));
  }
  set.properties = {{"centre_x", "m", x}, {"centre_y", "m", y}, {"neighbours", "1", neighbours}};
  for (const auto& [key, factors] : spread->factors())
    set.properties.push_back({"spread." + key, "1", factors});
  system.declare_members(std::move(set));
  build.publish(name, BundleFacts{bundle.members, expect_fan_command(node, name, air, build)});
}

const char* kExample = R"(scenario: {name: bundle_example, duration: 60 s, seed: 5}
output: {rate: 2 Hz}
bundle:
  count: 7
  packing: {layout: hexagonal, pitch: 1.2 mm}
  muscle:
    thermal: {heat_capacity: 0.05 J/K, conductance: 2 mW/K, ambient_temperature: 23 degC}
    thermal_force: {form: physical, force_per_kelvin: 4 mN/K, reference_temperature: 23 degC}
    mechanics: {k1: 10.8e-3 N/mm, k2: 2.7e-3 N/mm, damping: 4.3e-3 N*s/mm, force_offset: 0.1 N}
    resistance: {form: thermal, resistance: 9.4 ohm, temperature_coefficient: 6.41e-3 1/K, reference_temperature: 23 degC}
    inductance: {lambda_l: 107.4 uH*mm, lambda_x: 61 mm, lambda_0: 2.67 uH}
  spread: {mechanics.k1: {distribution: normal, relative: 0.05}, resistance.resistance: {distribution: uniform, relative: 0.02}}
  thermal: {shielding: 0.6, contact_conductance: 0.5 mW/K, fan: {conductance: 4 mW/K, speed: 0.5}}
  electrical: {wiring: parallel, voltage: 2 V, series_resistance: 0.1 ohm, energy_accounting: true}
load: {type: deflection, bundle: bundle, deflection: 20 mm}
)";

// Coupled coils, each muscle on its own Muscle Drive with its own estimator.
const char* kMagneticExample = R"(scenario: {name: bundle_example, duration: 2 s, seed: 5}
output: {rate: 20 Hz}
bundle:
  count: 3
  packing: {layout: hexagonal, pitch: 1.6 mm}
  muscle:
    thermal: {heat_capacity: 0.05 J/K, conductance: 2.5 mW/K, ambient_temperature: 23 degC}
    thermal_force: {form: physical, force_per_kelvin: 4 mN/K, reference_temperature: 23 degC}
    mechanics: {k1: 10.8e-3 N/mm, k2: 2.7e-3 N/mm, damping: 4.3e-3 N*s/mm, force_offset: 0.1 N}
    resistance: 10.18 ohm
    inductance: {lambda_l: 7.45 uH*mm, lambda_x: 28.8 mm, lambda_0: 1.148 uH}
  thermal: {shielding: 0.6}
  magnetic: {coil: {radius: 0.7 mm, turns: 62, length: 28.8 mm, wire_diameter: 0.1 mm}}
  electrical:
    wiring: individual
    drive: {model: muscle_drive, supply_voltage: 7 V, series_resistance: 0.57 ohm, measurement: {threshold_current: 14 mA}, power: 0.5 W}
    estimator:
      inductance: {lambda_l: 2.81 us*mm, lambda_x: 28.8 mm, lambda_0: 0.433 us}
      thermal: {kappa_P: 7.2e-3 N/J, kappa_c: 131.6e-3 1/s}
      mechanics: {k1: 10.8e-3 N/mm, k2: 2.7e-3 N/mm, damping: 4.3e-3 N*s/mm, force_offset: 106.9e-3 N}
      mutual_compensation: {coil: {radius: 0.7 mm, turns: 62, length: 28.8 mm, wire_diameter: 0.1 mm}, measure_per_henry: 0.3772 s/H}
load: {type: deflection, bundle: bundle, deflection: 20 mm}
)";

}  // namespace

void register_bundle_kind(KindRegistry& kinds) {
  kinds.add_category({kBundleCategory, "bundles", "", "",
                      "muscles in parallel between common end plates (a load holds them with "
                      "bundle: <name>): packed, heat-coupled, wired to one supply or each to "
                      "its own drive, with a seeded spread of their parameters",
                      "", 25});
  kinds.add({kBundleCategory,
             "parallel",
             "n muscles side by side (hexagonal or square packing); inner ones shielded "
             "from convection, touching ones exchanging heat, an optional fan (its speed a signal, "
             "or `controller` for a controller of type fan), coils coupled magnetically to their "
             "neighbours; wired in series "
             "or parallel to one supply (voltage, current or power) or each to its own drive",
             {{kExample, "bundle"}, {kMagneticExample, "bundle"}},
             InstanceBuilder(build_bundle)});
}

}  // namespace tcpmsim
