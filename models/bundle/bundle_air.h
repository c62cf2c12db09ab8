#pragma once

#include <memory>
#include <string>

#include "sim/parametric_component.h"
#include "sim/signal_reading.h"

namespace tcpmsim {

// The air in and around a bundle of muscles (its `thermal` section): how much of a muscle's
// free-air convection its neighbours block, the conductance between touching muscles, and a
// fan whose speed (0 to 1) adds forced convection: a prescribed signal, or (speed: controller)
// the input "fan_command" that a controller drives. The members' exchange terms
// (PackedHeatExchange) and their convective conductances read these from the run context, so
// that every pair of neighbours exchanges through one value and the bundle conserves energy.
struct BundleAirParameters {
  double shielding = 0.0;            // share of an inner muscle's convection its ring blocks
  double contact_conductance = 0.0;  // G_c between two touching muscles [W/K]
  double fan_conductance = 0.0;      // G_f added to a fully exposed muscle at full speed [W/K]
};

class BundleAir final : public ParametricComponent<BundleAirParameters> {
 public:
  enum Output { kFanSpeed };
  enum Input { kFanCommand };
  enum class Fan { none, prescribed, commanded };
  // A prescribed fan has its speed signal; the others have none.
  BundleAir(std::string group, BundleAirParameters defaults,
            ParameterBindings<BundleAirParameters> bindings, Fan fan,
            std::unique_ptr<Signal> fan_speed, double duration, bool contact = true);
  // Keys shielding, contact_conductance, fan: {conductance, speed: <signal> | controller}
  // (no fan: none).
  static std::unique_ptr<BundleAir> from_config(const std::string& group, const ConfigNode& node,
                                                const SignalContext& signals);

  std::vector<OutputDeclaration> outputs() const override { return {{"fan_speed", "1"}}; }
  std::vector<InputDeclaration> inputs() const override;
  std::vector<SignalDeclaration> signals() const override;
  Fan fan() const { return fan_; }
  // Whether touching muscles exchange heat (the scenario gives contact_conductance): without it
  // the members' temperatures are not coupled at all, and their Jacobian stays block-diagonal.
  bool contact() const { return contact_; }
  // A run's fan speed stays in [0, 1].
  std::string check_parameters(const RunSetup& setup) const override;
  void compute_outputs(const Evaluation& evaluation) const override;
  double next_breakpoint_after(const Evaluation& evaluation) const override;

 private:
  Fan fan_;
  std::unique_ptr<Signal> fan_speed_;  // a prescribed fan's
  double duration_;                    // of the scenario, over which the speed is checked
  bool contact_;
};

// One member's heat exchange inside the bundle, a heat-loss term of its thermal node:
//   to_neighbours = G_c sum_j (T - T_j)            over the touching muscles j,
//   to_fan        = f G_f s (T - T_amb)            f: the member's exposed fraction, s: fan speed.
// Summed over the bundle, to_neighbours cancels pair by pair: the contact moves heat, it loses
// none.
class PackedHeatExchange final : public Component {
 public:
  enum Input { kTemperature, kNeighbourTemperatures, kAmbientTemperature, kFanSpeed };
  enum Output { kToNeighbours, kToFan };
  // It has `neighbours` touching muscles of the `coordination` an inner one has, the sources of
  // neighbour_temperatures when the bundle has contact conduction; it reads the air's
  // parameters as the run context sets them.
  PackedHeatExchange(std::string group, const BundleAir& air, int neighbours, int coordination);

  std::vector<OutputDeclaration> outputs() const override;
  std::vector<InputDeclaration> inputs() const override;
  std::unique_ptr<RunState> create_run_state(const RunSetup& setup) const override;
  void compute_outputs(const Evaluation& evaluation) const override;

 private:
  const BundleAir& air_;
  int neighbours_;
  int coordination_;
};

}  // namespace tcpmsim
