#include "sim/scenario.h"

#include <cmath>

#include "controllers/joule_drive.h"
#include "controllers/muscle_drive.h"
#include "controllers/pid_controller.h"
#include "controllers/self_sensing_estimator.h"
#include "models/coil_impedance.h"
#include "models/coil_spring_chain.h"
#include "models/coil_spring_inductance.h"
#include "models/hanging_mass.h"
#include "models/imposed_load.h"
#include "models/sensor.h"
#include "models/sls_mechanics.h"
#include "models/thermal_force.h"
#include "models/thermal_node.h"
#include "signals/signal_config.h"

namespace tcpmsim {

namespace {

constexpr const char* kMuscle = "muscle";
constexpr const char* kDrive = "drive";
constexpr const char* kLoad = "load";

ScenarioSettings read_settings(const ConfigNode& root) {
  ScenarioSettings settings;
  root.declare({"scenario", "output", "solver", "muscle", "drive", "load", "spring", "estimator",
                "controller"});
  const ConfigNode scenario = root.at("scenario");
  scenario.declare({"name", "description", "duration", "seed"});
  settings.name = scenario.text("name");
  if (settings.name.empty() || settings.name.find_first_of("/\\ ") != std::string::npos) {
    scenario.at("name").fail(
        "expected a non-empty name without spaces or slashes (it names the output file)");
  }
  if (scenario.has("description")) settings.description = scenario.text("description");
  settings.duration = scenario.quantity("duration", "s", ValueCheck::positive());
  settings.seed =
      static_cast<std::uint64_t>(scenario.integer_or("seed", 0, ValueCheck::non_negative()));
  const ConfigNode output = root.at("output");
  output.declare({"rate", "start"});
  const double rate = output.quantity("rate", "Hz", ValueCheck::positive());
  settings.output_interval = 1.0 / rate;
  settings.output_start = output.quantity_or("start", "s", 0.0, ValueCheck::non_negative());
  if (settings.output_start >= settings.duration) {
    output.at("start").fail("expected a start before the end of the scenario (" +
                            std::to_string(settings.duration) + " s)");
  }
  return settings;
}

// What the load needs to know about the muscle.
struct MuscleSummary {
  SlsParameters mechanics;
  double initial_thermal_force = 0.0;
  std::function<double(const Context&)> initial_thermal_force_in;  // the same in a run
  bool has_temperature = false;
  const CoilImpedance* coil = nullptr;
};

MuscleSummary build_thermal(SystemBuilder& system, const ConfigNode& muscle,
                            const SignalContext& signals) {
  muscle.declare({"thermal", "thermal_force", "mechanics", "resistance", "inductance"});
  MuscleSummary summary;
  const ConfigNode thermal_force = muscle.at("thermal_force");
  const std::string form = thermal_force.choice("form", {"physical", "reduced"});
  if (form == "reduced") {
    if (muscle.has("thermal")) {
      muscle.at("thermal").fail(
          "the reduced thermal form (7.1) has no thermal node; remove muscle.thermal or use "
          "thermal_force.form: physical");
    }
    auto& reduced = system.add(ReducedThermalForce::from_config(kMuscle, thermal_force));
    system.connect(reduced, "power", "drive.power");
    summary.initial_thermal_force = reduced.defaults().initial_thermal_force;
    summary.initial_thermal_force_in = [](const Context& context) {
      return context.parameter("muscle.thermal_force.initial_thermal_force");
    };
    summary.has_temperature = reduced.defaults().force_per_kelvin.has_value();
    return summary;
  }
  auto& node = system.add(ThermalNode::from_config(kMuscle, muscle.at("thermal"), signals));
  system.connect(node, "power", "drive.power");
  auto& force = system.add(PhysicalThermalForce::from_config(kMuscle, thermal_force));
  system.connect(force, "temperature", "muscle.temperature");
  // The thermal node starts at its initial temperature; F_T follows from it.
  summary.initial_thermal_force =
      force.defaults().force_per_kelvin *
      (node.initial_temperature(0.0) - force.defaults().reference_temperature);
  const bool initial_given = node.defaults().initial_temperature.has_value();
  summary.initial_thermal_force_in = [initial_given](const Context& context) {
    const double start =
        initial_given
            ? context.parameter("muscle.thermal.initial_temperature")
            : context.signal(*context.system().signal_slot("muscle", "ambient_temperature"))
                  .value(0.0);
    return context.parameter("muscle.thermal_force.force_per_kelvin") *
           (start - context.parameter("muscle.thermal_force.reference_temperature"));
  };
  summary.has_temperature = true;
  return summary;
}

MuscleSummary build_muscle(SystemBuilder& system, const ConfigNode& muscle, bool force_imposed,
                           const SignalContext& signals) {
  MuscleSummary summary = build_thermal(system, muscle, signals);
  auto& mechanics = system.add(SlsMechanics::from_config(kMuscle, muscle.at("mechanics")));
  summary.mechanics = mechanics.defaults();
  system.connect(mechanics, "thermal_force", "muscle.thermal_force");
  if (force_imposed) {
    system.connect(mechanics, "force", "load.force");
  } else {
    system.connect(mechanics, "deflection", "load.deflection");
  }
  const ConfigNode resistance = muscle.at("resistance");
  const ConfigNode inductance = muscle.at("inductance");
  auto& coil = system.add(CoilImpedance::from_config(kMuscle, inductance, resistance));
  system.connect(coil, "deflection", "muscle.deflection");
  if (coil.needs_temperature()) {
    if (!summary.has_temperature) {
      (coil.defaults().resistance_law().rho_T != 0.0 ? resistance : inductance)
          .fail(
              "depends on temperature, but the reduced thermal form reports none; give "
              "muscle.thermal_force.force_per_kelvin");
    }
    system.connect(coil, "temperature", "muscle.temperature");
  }
  summary.coil = &coil;
  return summary;
}

void check_deflection_range(const ConfigNode& node, const Signal& deflection,
                            const MuscleSummary& muscle, double duration) {
  const double lowest = deflection.range(0.0, duration).first;
  const double singular = -muscle.coil->defaults().inductance.lambda_x;
  if (!(lowest > singular)) {
    node.fail("the deflection reaches " + std::to_string(lowest) + " m, at or below -lambda_x = " +
              std::to_string(singular) + " m where the inductance law (6.3) is singular");
  }
}

void add_sensor(SystemBuilder& system, const ConfigNode& load, const std::string& name,
                const std::string& unit, const std::string& source, const char* resolution_key) {
  auto& sensor = system.add(Sensor::from_config(kLoad, name, unit, load, resolution_key));
  system.connect(sensor, "measured", source);
}

void build_load(SystemBuilder& system, const ConfigNode& load, const std::string& type,
                const MuscleSummary& muscle, const SignalContext& signals) {
  load.declare({"type", "deflection", "force", "mass", "gravity", "damping", "initial_deflection",
                "initial_velocity", "load_cell_resolution", "position_resolution"});
  if (type == "deflection") {
    const ConfigNode signal_node = load.at("deflection");
    auto signal = read_signal(signal_node, "m", signals);
    check_deflection_range(signal_node, *signal, muscle, signals.duration);
    system.add(
        std::make_unique<ImposedLoad>(kLoad, ImposedLoad::Quantity::deflection, std::move(signal)));
    add_sensor(system, load, "force", "N", "muscle.force", "load_cell_resolution");
  } else if (type == "force") {
    system.add(std::make_unique<ImposedLoad>(kLoad, ImposedLoad::Quantity::force,
                                             read_signal(load.at("force"), "N", signals)));
    add_sensor(system, load, "deflection", "m", "muscle.deflection", "position_resolution");
  } else {
    // Static balance of (7.5) with a relaxed dashpot: m g = k1 x + F_T(0) + phi_0.
    const auto equilibrium = [muscle](double weight) {
      return (weight - muscle.initial_thermal_force - muscle.mechanics.force_offset) /
             muscle.mechanics.k1;
    };
    bool at_equilibrium = false;
    auto& mass = system.add(HangingMass::from_config(kLoad, load, equilibrium, &at_equilibrium));
    if (at_equilibrium) {
      system.derive(
          "load.initial_deflection",
          [muscle](const Context& context) {
            return (context.parameter("load.mass") * context.parameter("load.gravity") -
                    muscle.initial_thermal_force_in(context) -
                    context.parameter("muscle.mechanics.force_offset")) /
                   context.parameter("muscle.mechanics.k1");
          },
          "the static balance m g = k1 x + F_T + phi_0");
    }
    system.connect(mass, "force", "muscle.force");
    add_sensor(system, load, "force", "N", "muscle.force", "load_cell_resolution");
  }
}

void read_absolute_tolerances(const ConfigNode& solver, const System& system,
                              SolverSettings& settings) {
  settings.absolute_tolerances.clear();
  const auto overrides = solver.find("atol");
  for (const auto& state : system.states()) {
    double tolerance = state.absolute_tolerance;
    const auto dot = state.name.find('.');
    const std::string group = state.name.substr(0, dot), name = state.name.substr(dot + 1);
    if (overrides) {
      if (auto group_node = overrides->find(group)) {
        if (auto value = group_node->find(name))
          tolerance = value->as_quantity(state.unit, ValueCheck::positive());
      }
    }
    settings.absolute_tolerances.push_back(tolerance);
  }
}

SolverSettings read_solver(const ConfigNode& root, const System& system) {
  SolverSettings settings;
  const auto solver = root.find("solver");
  if (!solver) {
    for (const auto& state : system.states())
      settings.absolute_tolerances.push_back(state.absolute_tolerance);
    return settings;
  }
  solver->declare(
      {"method", "rtol", "atol", "linear_solver", "max_step", "initial_step", "max_steps"});
  settings.method = solver->choice_or("method", {"bdf", "adams"}, "bdf") == "adams"
                        ? IntegrationMethod::adams
                        : IntegrationMethod::bdf;
  settings.relative_tolerance =
      solver->number_or("rtol", settings.relative_tolerance, ValueCheck::between(1e-14, 0.1));
  const std::string kind = solver->choice_or("linear_solver", {"dense", "band", "klu"}, "dense");
  settings.linear_solver = kind == "band"  ? LinearSolverKind::band
                           : kind == "klu" ? LinearSolverKind::klu
                                           : LinearSolverKind::dense;
  settings.max_step = solver->quantity_or("max_step", "s", 0.0, ValueCheck::non_negative());
  settings.initial_step = solver->quantity_or("initial_step", "s", 0.0, ValueCheck::non_negative());
  settings.max_steps = solver->integer_or("max_steps", settings.max_steps, ValueCheck::at_least(1));
  read_absolute_tolerances(*solver, system, settings);
  return settings;
}

// The self-sensing estimator and the controller (thesis 7.2.3-7.2.4), sampled with the Muscle
// Drive's PWM: the estimator reads the drive's L* and the power it was asked for, the controller
// the estimate of what it controls.
void build_self_sensing(SystemBuilder& system, const ConfigNode& root, const MuscleDrive& drive,
                        const SignalContext& signals) {
  const double period = 1.0 / drive.defaults().pwm_frequency;
  const bool controlled = root.has("controller");
  if (!root.has("estimator")) {
    if (controlled) root.at("controller").fail("a controller needs an estimator section to read");
    return;
  }
  auto& estimator =
      system.add(SelfSensingEstimator::from_config("estimator", root.at("estimator"), period));
  system.derive(
      "estimator.sample_period",
      [](const Context& context) { return 1.0 / context.parameter("drive.pwm_frequency"); },
      "1 / drive.pwm_frequency");
  system.connect(estimator, "inductance_measure", "drive.inductance_measure");
  system.connect(estimator, "power_command",
                 controlled ? "controller.power_command" : "drive.power_demand");
  if (!controlled) return;
  auto& controller =
      system.add(PidController::from_config("controller", root.at("controller"), period, signals));
  system.derive(
      "controller.sample_period",
      [](const Context& context) { return 1.0 / context.parameter("drive.pwm_frequency"); },
      "1 / drive.pwm_frequency");
  system.connect(controller, "estimate",
                 controller.target() == PidController::Target::deflection ? "estimator.deflection"
                                                                          : "estimator.force");
}

// `joule`: a prescribed duty, power or current, period-averaged. `muscle_drive`: the thesis'
// Muscle Drive, averaged or switched, measuring L*.
void build_drive(SystemBuilder& system, const ConfigNode& root, const MuscleSummary& muscle,
                 const SignalContext& signals) {
  const ConfigNode drive = root.at("drive");
  if (drive.choice_or("model", {"joule", "muscle_drive"}, "joule") == "joule") {
    for (const char* section : {"estimator", "controller"}) {
      if (root.has(section))
        root.at(section).fail("self-sensing needs the Muscle Drive (drive.model: muscle_drive)");
    }
    auto& joule = system.add(JouleDrive::from_config(kDrive, drive, signals));
    if (joule.needs_resistance()) system.connect(joule, "heater_resistance", "muscle.resistance");
    return;
  }
  if (muscle.coil->defaults().inductance.is_measure) {
    drive.fail(
        "the Muscle Drive measures the coil's decay time itself: give muscle.inductance in henries "
        "(quantity: inductance), not as a measure");
  }
  const bool controlled = root.has("controller");
  auto& muscle_drive = system.add(MuscleDrive::from_config(kDrive, drive, signals, controlled));
  system.connect(muscle_drive, "heater_resistance", "muscle.resistance");
  system.connect(muscle_drive, "inductance", "muscle.inductance");
  if (controlled) system.connect(muscle_drive, "power_command", "controller.power_command");
  build_self_sensing(system, root, muscle_drive, signals);
}

// The muscle with its drive and load (thesis ch. 6-7).
void build_muscle_system(SystemBuilder& system, const ConfigNode& root,
                         const SignalContext& signals) {
  const ConfigNode load = root.at("load");
  const std::string load_type = load.choice("type", {"deflection", "force", "hanging_mass"});
  const MuscleSummary muscle =
      build_muscle(system, root.at("muscle"), load_type == "force", signals);
  build_drive(system, root, muscle, signals);
  build_load(system, load, load_type, muscle, signals);
}

// A metal coil spring between two imposed end motions (thesis ch. 4).
void build_spring_system(SystemBuilder& system, const ConfigNode& spring,
                         const SignalContext& signals) {
  spring.declare({"windings", "rest_length", "mass", "stiffness", "damping_ratio",
                  "initial_velocity", "first_end", "second_end", "inductance"});
  auto& chain = system.add(CoilSpringChain::from_config("spring", spring, signals));
  const auto inductance = spring.find("inductance");
  if (!inductance) return;
  const double initial_length = chain.end_position(1, 0.0) - chain.end_position(0, 0.0);
  auto& sensor = system.add(CoilSpringInductance::from_config(
      "spring", *inductance, chain.defaults(), initial_length, "spring"));
  for (const auto& input : sensor.inputs())
    system.connect(sensor, input.name, "spring." + input.name);
}

}  // namespace

Scenario build_scenario(const ConfigNode& root) {
  Scenario scenario;
  scenario.settings = read_settings(root);
  const SignalContext signals{scenario.settings.seed, scenario.settings.duration};
  SystemBuilder system;

  if (root.has("spring")) {
    build_spring_system(system, root.at("spring"), signals);
  } else if (root.has("muscle") || root.has("drive") || root.has("load")) {
    build_muscle_system(system, root, signals);
  } else {
    root.fail("expected a 'muscle' section (with 'drive' and 'load') or a 'spring' section");
  }

  try {
    scenario.system = system.build();
  } catch (const std::logic_error& error) {
    root.fail(std::string("the scenario does not assemble: ") + error.what());
  }
  scenario.solver = read_solver(root, *scenario.system);
  root.reject_unknown_keys();
  scenario.resolved_yaml = root.resolved_yaml();
  return scenario;
}

Context Scenario::make_context() const {
  return Context(*system);
}

Scenario load_scenario(const std::string& file, const std::vector<std::string>& overrides,
                       std::shared_ptr<const UnitSystem> units) {
  Scenario scenario = build_scenario(ConfigNode::load_file(file, overrides, std::move(units)));
  scenario.source = file;
  return scenario;
}

}  // namespace tcpmsim
