#pragma once

#include <memory>
#include <optional>

#include "models/laws/impedance.h"
#include "sim/component.h"
#include "sim/config/config_node.h"
#include "sim/parameter_bindings.h"

namespace tcpmsim {

// The heater coil's impedance parameters as a scenario states them: the inductance law (6.3)/
// (7.3) directly, the resistance as a constant, the linear law (6.5) or the thermal law (6.4)
// R0 (1 + kappa (T - T0)) + rho_x x.
struct CoilImpedanceParameters {
  bool has_inductance = true;  // false: a muscle without self-sensing states no inductance law
  InductanceLaw inductance;
  enum class ResistanceForm { constant, linear, thermal };
  ResistanceForm resistance_form = ResistanceForm::constant;
  ResistanceLaw resistance;              // constant (rho_0) and linear forms
  double thermal_resistance = 0.0;       // R0 [ohm] of the thermal form
  double temperature_coefficient = 0.0;  // kappa [1/K]
  double thermal_reference = 0.0;        // T0 [K]
  double strain_coefficient = 0.0;       // rho_x [ohm/m]
  ResistanceLaw resistance_law() const;
};

// The heater coil's impedance as seen by a drive or an LCR meter: inductance (or the Muscle
// Drive's measure L*) by (6.3)/(7.3) and resistance by (6.5)/(6.4), from the muscle's
// deflection and temperature. The drive heats with this resistance, so R(T) of an iron wire
// feeds back into the Joule heating. The fan-in input "mutual_inductances" adds the mutual
// inductance of coupled coils to the inductance (henries only): a bundle's neighbours. Without an
// inductance law (nothing reads the coil's inductance) only the resistance is an output.
class CoilImpedance final : public Component {
 public:
  enum Input { kDeflection, kTemperature };
  enum Output { kInductance, kResistance };  // without an inductance law: the resistance only
  CoilImpedance(std::string group, CoilImpedanceParameters defaults,
                ParameterBindings<CoilImpedanceParameters> bindings);
  // Reads `inductance` (if given) and `resistance` (keys above).
  static std::unique_ptr<CoilImpedance> from_config(const std::string& group,
                                                    const std::optional<ConfigNode>& inductance,
                                                    const ConfigNode& resistance);

  std::vector<OutputDeclaration> outputs() const override;
  std::vector<InputDeclaration> inputs() const override;
  std::vector<ParameterDeclaration> parameters() const override;
  std::unique_ptr<RunState> create_run_state(const RunSetup& setup) const override;
  std::string check_parameters(const RunSetup& setup) const override;
  void compute_outputs(const Evaluation& evaluation) const override;

  std::string check_connections() const override;
  // The index of the input "mutual_inductances" (after deflection and, if any, temperature).
  int mutual_input() const { return needs_temperature() ? 2 : 1; }
  // Whether the impedance depends on temperature (as built).
  bool needs_temperature() const { return temperature_dependent_; }
  bool has_inductance() const { return defaults_.has_inductance; }
  const CoilImpedanceParameters& defaults() const { return defaults_; }

 private:
  struct Run;
  CoilImpedanceParameters defaults_;
  ParameterBindings<CoilImpedanceParameters> bindings_;
  bool temperature_dependent_;
};

}  // namespace tcpmsim
