#pragma once

#include <memory>

#include "sim/config/config_node.h"
#include "sim/parametric_component.h"

namespace tcpmsim {

// An irreversible ratchet of the muscle's rest length: above a threshold temperature the
// polymer creeps, and what it gains in length it keeps when it cools (a nylon TCPM loses
// tension with each heating cycle until it is trained). As the force it costs,
//     dF_r/dt = -g max(0, T - T_th),     F_r(0) = 0,
// which never rises again: F_r = -k1 dl with dl the rest length gained, here folded into g
// [N/(K s)] so that the term needs no other component's parameter. It enters the force balance
// as an offset (F = F_r, no stiffness) and carries none at the start; with g = 0 it carries
// none ever (discover's nested start).
struct RatchetParameters {
  double rate = 0.0;       // g [N/(K s)]
  double threshold = 0.0;  // T_th [K]
};

namespace ratchet {
// dF_r/dt [N/s] at temperature T.
inline double force_rate(const RatchetParameters& p, double temperature) {
  const double excess = temperature - p.threshold;
  return excess > 0.0 ? -p.rate * excess : 0.0;
}
}  // namespace ratchet

class Ratchet final : public ParametricComponent<RatchetParameters> {
 public:
  enum Input { kTemperature };
  enum Output { kStiffness, kOffsetForce, kRestStiffness, kRestForce, kForce };
  Ratchet(std::string group, RatchetParameters defaults,
          ParameterBindings<RatchetParameters> bindings = {});
  // Keys rate, threshold.
  static std::unique_ptr<Ratchet> from_config(const std::string& group, const ConfigNode& node);

  std::vector<StateDeclaration> states() const override { return {{"force", "N", 1e-10}}; }
  std::vector<OutputDeclaration> outputs() const override;
  std::vector<InputDeclaration> inputs() const override { return {{"temperature", false}}; }
  void initialize(const Evaluation& evaluation, std::span<double> own_state) const override;
  void compute_outputs(const Evaluation& evaluation) const override;
  void compute_derivatives(const Evaluation& evaluation, double* derivatives) const override;
};

}  // namespace tcpmsim
