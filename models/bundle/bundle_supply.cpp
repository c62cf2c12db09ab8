#include "models/bundle/bundle_supply.h"

namespace tcpmsim {

namespace {
constexpr const char* kSourceUnit[] = {"V", "A", "W"};  // by SupplyMode
constexpr const char* kSourceKey[] = {"voltage", "current", "power"};

// What is wrong with the source over [0, duration], or "": a power cannot be negative.
std::string source_problem(SupplyMode mode, const Signal& source, double duration) {
  if (mode == SupplyMode::power && source.range(0.0, duration).first < 0.0)
    return "expected a power that stays at or above 0 W";
  return {};
}
}  // namespace

BundleSupply::BundleSupply(std::string group, BundleWiring wiring, SupplyMode mode,
                           BundleSupplyParameters defaults,
                           ParameterBindings<BundleSupplyParameters> bindings,
                           std::unique_ptr<Signal> source, double duration, bool energy_accounting)
    : ParametricComponent(std::move(group), "bundle_supply", defaults, std::move(bindings)),
      wiring_(wiring),
      mode_(mode),
      source_(std::move(source)),
      duration_(duration),
      energy_accounting_(energy_accounting) {}

std::unique_ptr<BundleSupply> BundleSupply::from_config(const std::string& group,
                                                        const ConfigNode& node, BundleWiring wiring,
                                                        const SignalContext& signals) {
  node.declare({"voltage", "current", "power", "series_resistance", "energy_accounting"});
  int given = 0;
  SupplyMode mode = SupplyMode::voltage;
  for (const auto candidate : {SupplyMode::voltage, SupplyMode::current, SupplyMode::power}) {
    if (node.has(kSourceKey[static_cast<int>(candidate)])) {
      mode = candidate;
      ++given;
    }
  }
  if (given != 1) node.fail("expected exactly one of voltage, current or power (the supply's)");
  const ConfigNode source_node = node.at(kSourceKey[static_cast<int>(mode)]);
  auto source = read_signal(source_node, kSourceUnit[static_cast<int>(mode)], signals);
  if (const std::string problem = source_problem(mode, *source, signals.duration); !problem.empty())
    source_node.fail(problem);
  BundleSupplyParameters p;
  ParameterBindings<BundleSupplyParameters> bind;
  bind.quantity_or(node, "series_resistance", "ohm", 0.0, ValueCheck::non_negative(), p,
                   bind.member(&BundleSupplyParameters::series_resistance));
  const bool accounting = node.boolean_or("energy_accounting", false);
  return std::make_unique<BundleSupply>(group, wiring, mode, p, std::move(bind), std::move(source),
                                        signals.duration, accounting);
}

std::vector<StateDeclaration> BundleSupply::states() const {
  if (!energy_accounting_) return {};
  return {{"energy", "J", 1e-9}, {"series_heat", "J", 1e-9}};
}

std::vector<OutputDeclaration> BundleSupply::outputs() const {
  std::vector<OutputDeclaration> declared{
      {"voltage", "V"}, {"current", "A"}, {"power", "W"}, {"source_power", "W"}};
  if (energy_accounting_) {
    declared.push_back({"energy", "J"});
    declared.push_back({"series_heat", "J"});
  }
  return declared;
}

std::vector<InputDeclaration> BundleSupply::inputs() const {
  return {{"resistance", true, false, InputArity::many, true}};
}

std::vector<SignalDeclaration> BundleSupply::signals() const {
  return {{"source", kSourceUnit[static_cast<int>(mode_)], source_.get()}};
}

std::string BundleSupply::check_parameters(const RunSetup& setup) const {
  const std::string problem = source_problem(mode_, signal(setup.context, 0), duration_);
  return problem.empty() ? problem
                         : std::string(kSourceKey[static_cast<int>(mode_)]) + ": " + problem;
}

void BundleSupply::initialize(const Evaluation&, std::span<double> own_state) const {
  for (double& value : own_state) value = 0.0;
}

OperatingPoint BundleSupply::operating_point(const Evaluation& evaluation) const {
  double sum = 0.0;
  for (int k = 0; k < source_count(kResistances); ++k) {
    sum += bundle_circuit::resistance_term(wiring_, input(evaluation, kResistances, k));
  }
  return bundle_circuit::operating_point(mode_, signal(evaluation, 0).value(evaluation.signal_time),
                                         run_parameters(evaluation).series_resistance,
                                         bundle_circuit::resistance(wiring_, sum));
}

void BundleSupply::compute_outputs(const Evaluation& evaluation) const {
  const OperatingPoint point = operating_point(evaluation);
  set_output(evaluation, kVoltage, point.voltage);
  set_output(evaluation, kCurrent, point.current);
  set_output(evaluation, kPower, point.voltage * point.current);
  set_output(evaluation, kSourcePower,
             bundle_circuit::source_power(point, run_parameters(evaluation).series_resistance));
  if (energy_accounting_) {
    set_output(evaluation, kEnergy, state(evaluation, 0));
    set_output(evaluation, kSeriesHeat, state(evaluation, 1));
  }
}

void BundleSupply::compute_derivatives(const Evaluation& evaluation, double* derivatives) const {
  if (!energy_accounting_) return;
  const OperatingPoint point = operating_point(evaluation);
  set_derivative(derivatives, 0,
                 bundle_circuit::source_power(point, run_parameters(evaluation).series_resistance));
  set_derivative(derivatives, 1,
                 run_parameters(evaluation).series_resistance * point.current * point.current);
}

double BundleSupply::next_breakpoint_after(const Evaluation& evaluation) const {
  return signal(evaluation, 0).next_breakpoint_after(evaluation.time);
}

MemberWire::MemberWire(std::string group, BundleWiring wiring)
    : Component(std::move(group), "member_wire"), wiring_(wiring) {}

std::vector<OutputDeclaration> MemberWire::outputs() const {
  return {{"current", "A"}, {"voltage", "V"}, {"power", "W"}};
}

std::vector<InputDeclaration> MemberWire::inputs() const {
  return {{"resistance", true}, {"bundle_voltage", true}, {"bundle_current", true}};
}

void MemberWire::compute_outputs(const Evaluation& evaluation) const {
  const double resistance = input(evaluation, kResistance);
  const OperatingPoint bundle{input(evaluation, kBundleVoltage), input(evaluation, kBundleCurrent)};
  const double current = bundle_circuit::member_current(wiring_, bundle, resistance);
  set_output(evaluation, kCurrent, current);
  set_output(evaluation, kVoltage, current * resistance);
  set_output(evaluation, kPower, current * current * resistance);
}

}  // namespace tcpmsim
