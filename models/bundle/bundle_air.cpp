#include "models/bundle/bundle_air.h"

#include <stdexcept>

#include "models/laws/packing.h"
#include "models/typical_values.h"
#include "sim/context.h"

namespace tcpmsim {

namespace {

// What is wrong with a fan speed over [0, duration], or "".
std::string fan_speed_problem(const Signal& speed, double duration) {
  const auto [low, high] = speed.range(0.0, duration);
  if (low < 0.0 || high > 1.0) return "expected a fan speed between 0 (off) and 1 (full)";
  return {};
}
}  // namespace

BundleAir::BundleAir(std::string group, BundleAirParameters defaults,
                     ParameterBindings<BundleAirParameters> bindings, Fan fan,
                     std::unique_ptr<Signal> fan_speed, double duration, bool contact)
    : ParametricComponent(std::move(group), "bundle_air", defaults, std::move(bindings)),
      fan_(fan),
      fan_speed_(std::move(fan_speed)),
      duration_(duration),
      contact_(contact) {
  if ((fan_ == Fan::prescribed) != (fan_speed_ != nullptr))
    throw std::invalid_argument("BundleAir: a speed signal exactly when the fan is prescribed");
}

std::unique_ptr<BundleAir> BundleAir::from_config(const std::string& group, const ConfigNode& node,
                                                  const SignalContext& signals) {
  node.declare({"shielding", "contact_conductance", "fan"});
  BundleAirParameters p;
  ParameterBindings<BundleAirParameters> bind;
  bind.quantity(node, "shielding", "1", ValueCheck::fraction(), p,
                bind.member(&BundleAirParameters::shielding));
  const bool contact = node.has("contact_conductance");
  bind.quantity_or(node, "contact_conductance", "W/K", 0.0,
                   typical::added_conductance(ValueCheck::non_negative()), p,
                   bind.member(&BundleAirParameters::contact_conductance));
  std::unique_ptr<Signal> speed;
  Fan kind = Fan::none;
  if (const auto fan = node.find("fan")) {
    fan->declare({"conductance", "speed"});
    bind.quantity(*fan, "conductance", "W/K",
                  typical::added_conductance(ValueCheck::non_negative()), p,
                  bind.member(&BundleAirParameters::fan_conductance));
    const ConfigNode speed_node = fan->at("speed");
    kind = speed_node.is_word("controller") ? Fan::commanded : Fan::prescribed;
    if (kind == Fan::prescribed) {
      speed = read_signal(speed_node, "1", signals);
      if (const std::string problem = fan_speed_problem(*speed, signals.duration); !problem.empty())
        speed_node.fail(problem);
    }
  }
  return std::make_unique<BundleAir>(group, p, std::move(bind), kind, std::move(speed),
                                     signals.duration, contact);
}

std::vector<InputDeclaration> BundleAir::inputs() const {
  if (fan_ != Fan::commanded) return {};
  return {{"fan_command", true}};
}

std::vector<SignalDeclaration> BundleAir::signals() const {
  if (!fan_speed_) return {};
  return {{"fan_speed", "1", fan_speed_.get()}};
}

std::string BundleAir::check_parameters(const RunSetup& setup) const {
  if (!contact_ && parameters_in(setup.context).contact_conductance != 0.0) {
    return "contact_conductance: this bundle was assembled without contact conduction; give "
           "thermal.contact_conductance in the scenario to couple its muscles";
  }
  if (!fan_speed_) return {};
  const std::string problem = fan_speed_problem(signal(setup.context, 0), duration_);
  return problem.empty() ? problem : "fan.speed: " + problem;
}

void BundleAir::compute_outputs(const Evaluation& evaluation) const {
  double speed = 0.0;
  if (fan_ == Fan::prescribed) speed = signal(evaluation, 0).value(evaluation.signal_time);
  if (fan_ == Fan::commanded) speed = input(evaluation, kFanCommand);
  set_output(evaluation, kFanSpeed, speed);
}

double BundleAir::next_breakpoint_after(const Evaluation& evaluation) const {
  return fan_speed_ ? signal(evaluation, 0).next_breakpoint_after(evaluation.time) : kNoBreakpoint;
}

namespace {
struct ExchangeRun final : RunState {
  double contact_conductance = 0.0;
  double fan_conductance = 0.0;  // f G_f for this member
};
}  // namespace

PackedHeatExchange::PackedHeatExchange(std::string group, const BundleAir& air, int neighbours,
                                       int coordination)
    : Component(std::move(group), "packed_heat_exchange"),
      air_(air),
      neighbours_(neighbours),
      coordination_(coordination) {}

std::vector<OutputDeclaration> PackedHeatExchange::outputs() const {
  return {{"to_neighbours", "W"}, {"to_fan", "W"}};
}

std::vector<InputDeclaration> PackedHeatExchange::inputs() const {
  return {{"temperature", true},
          {"neighbour_temperatures", true, false, InputArity::many, true},
          {"ambient_temperature", true},
          {"fan_speed", true}};
}

std::unique_ptr<RunState> PackedHeatExchange::create_run_state(const RunSetup& setup) const {
  auto run = std::make_unique<ExchangeRun>();
  const BundleAirParameters air = air_.parameters_in(setup.context);
  run->contact_conductance = air.contact_conductance;
  run->fan_conductance =
      packing::exposed_fraction(neighbours_, coordination_, air.shielding) * air.fan_conductance;
  return run;
}

void PackedHeatExchange::compute_outputs(const Evaluation& evaluation) const {
  const auto& run = run_state<ExchangeRun>(evaluation);
  const double temperature = input(evaluation, kTemperature);
  // G_c sum_j (T - T_j), difference by difference: n T - sum T_j would cancel ~300 K values
  // and leave rounding where neighbours are equal, so the bundle would no longer conserve heat
  // exactly.
  double difference = 0.0;
  for (int k = 0; k < source_count(kNeighbourTemperatures); ++k)
    difference += temperature - input(evaluation, kNeighbourTemperatures, k);
  set_output(evaluation, kToNeighbours, run.contact_conductance * difference);
  set_output(evaluation, kToFan,
             run.fan_conductance * input(evaluation, kFanSpeed) *
                 (temperature - input(evaluation, kAmbientTemperature)));
}

}  // namespace tcpmsim
