#pragma once

#include <memory>
#include <string>

#include "models/laws/bundle_circuit.h"
#include "sim/parametric_component.h"
#include "sim/signal_reading.h"

namespace tcpmsim {

// One supply for all the muscles of a bundle, wired in series or in parallel (the bundle's
// `electrical` section). It holds a voltage behind a series resistance, a current, or the power
// into the bundle (a signal), reads every member's resistance R_k(T, x), and gives the bundle's
// terminal voltage and current (bundle_circuit). Each member's MemberWire takes its share.
// With energy_accounting it integrates the energy its source gives, V I + R_s I^2 (the bundle's
// power and the series resistance's heat), so that a bundle's energy balance can be checked.
struct BundleSupplyParameters {
  double series_resistance = 0.0;  // R_s [ohm]
};

class BundleSupply final : public ParametricComponent<BundleSupplyParameters> {
 public:
  enum Input { kResistances };
  enum Output { kVoltage, kCurrent, kPower, kSourcePower, kEnergy, kSeriesHeat };
  BundleSupply(std::string group, BundleWiring wiring, SupplyMode mode,
               BundleSupplyParameters defaults, ParameterBindings<BundleSupplyParameters> bindings,
               std::unique_ptr<Signal> source, double duration, bool energy_accounting);
  // Keys: one of voltage / current / power (a signal), series_resistance, energy_accounting.
  static std::unique_ptr<BundleSupply> from_config(const std::string& group, const ConfigNode& node,
                                                   BundleWiring wiring,
                                                   const SignalContext& signals);

  std::vector<StateDeclaration> states() const override;
  std::vector<OutputDeclaration> outputs() const override;
  std::vector<InputDeclaration> inputs() const override;
  std::vector<SignalDeclaration> signals() const override;
  // A run's power stays at or above 0 W.
  std::string check_parameters(const RunSetup& setup) const override;
  void initialize(const Evaluation& evaluation, std::span<double> own_state) const override;
  void compute_outputs(const Evaluation& evaluation) const override;
  void compute_derivatives(const Evaluation& evaluation, double* derivatives) const override;
  double next_breakpoint_after(const Evaluation& evaluation) const override;

 private:
  OperatingPoint operating_point(const Evaluation& evaluation) const;

  BundleWiring wiring_;
  SupplyMode mode_;
  std::unique_ptr<Signal> source_;
  double duration_;  // of the scenario, over which the source is checked
  bool energy_accounting_;
};

// A member's share of its bundle's supply: its current (the bundle's in series, V / R in
// parallel), its voltage and the power it takes, I^2 R, which heats it.
class MemberWire final : public Component {
 public:
  enum Input { kResistance, kBundleVoltage, kBundleCurrent };
  enum Output { kCurrent, kVoltage, kPower };
  MemberWire(std::string group, BundleWiring wiring);

  std::vector<OutputDeclaration> outputs() const override;
  std::vector<InputDeclaration> inputs() const override;
  void compute_outputs(const Evaluation& evaluation) const override;

 private:
  BundleWiring wiring_;
};

}  // namespace tcpmsim
