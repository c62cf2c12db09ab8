#pragma once

#include "models/laws/impedance.h"
#include "sim/component.h"
#include "sim/config/config_node.h"

namespace tcpmsim {

// (6.3)/(7.3) from its keys; `quantity: measure` gives the Muscle Drive's L* instead of henries.
InductanceLaw read_inductance_law(const ConfigNode& node);
// A scalar is a constant resistance (constantan); a mapping has form linear (6.5) or
// thermal (6.4).
ResistanceLaw read_resistance_law(const ConfigNode& node);

// The heater coil's impedance as seen by a drive or an LCR meter: inductance (or the Muscle
// Drive's measure L*) by (6.3)/(7.3) and resistance by (6.5)/(6.4), from the muscle's
// deflection and temperature. The drive heats with this resistance, so R(T) of an iron wire
// feeds back into the Joule heating.
class CoilImpedance final : public Component {
 public:
  enum Output { kInductance, kResistance };
  CoilImpedance(std::string group, InductanceLaw inductance, ResistanceLaw resistance);

  std::vector<OutputDeclaration> outputs() const override;
  std::vector<InputDeclaration> inputs() const override;
  void compute_outputs(const Evaluation& evaluation) const override;

  bool needs_temperature() const;
  const InductanceLaw& inductance() const { return inductance_; }
  const ResistanceLaw& resistance() const { return resistance_; }

 private:
  InductanceLaw inductance_;
  ResistanceLaw resistance_;
};

}  // namespace tcpmsim
