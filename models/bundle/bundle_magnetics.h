#pragma once

#include <memory>
#include <string>
#include <vector>

#include "models/inductance/coil_geometry.h"
#include "sim/component.h"
#include "sim/config/config_node.h"

namespace tcpmsim {

// The mutual inductance of two touching members of a bundle, coils side by side at the packing
// pitch, as a function of their common deflection: M(l0 + x) of
// inductance::parallel_coils_mutual_inductance (Neumann's formula over every pair of rings),
// interpolated at Chebyshev nodes over coil lengths from l0/4 to 4 l0 (within 1e-6 of the direct
// sum between the nodes, or std::domain_error at construction) and held at its ends outside.
// Fixed at assembly: the geometry is not a run parameter.
class NeighbourMutual {
 public:
  NeighbourMutual(inductance::CoilGeometry at_rest, double separation);
  // Keys coil: {radius (to the wire centre), turns, length (at zero deflection), wire_diameter};
  // separation is the packing pitch.
  static std::shared_ptr<const NeighbourMutual> from_config(const ConfigNode& node,
                                                            double separation);
  double operator()(double deflection) const;          // [H]
  double direct(double deflection) const;              // the library's sum, without the table
  double table_error() const { return table_error_; }  // relative, between the nodes

 private:
  inductance::CoilGeometry at_rest_;
  double separation_;
  double interpolate(double u) const;
  double shortest_, longest_;                     // the table's ends, ln of the coil length
  std::vector<double> nodes_, weights_, values_;  // first-kind Chebyshev nodes, in u
  double table_error_ = 0.0;
};

// What a member's coupling component ("<member>/magnetic") tells instances built after it: the
// packing an estimator needs for its own model of the coupling (plant and model stay separate).
struct MemberCouplingFacts {
  int neighbours = 0;  // touching coils
  double pitch = 0.0;  // [m] between their axes
};

// One member's magnetic coupling, a term of its coil's inductance: n M(x), with n its touching
// neighbours. Coupled in full because the members' Muscle Drives switch together (the same PWM
// frequency from the same start): every coil's current decays with its neighbours', and
// L di/dt + sum_j M dij/dt = (L + n M) di/dt for equal decays. Output "mutual_inductance" [H].
class MemberMutual final : public Component {
 public:
  MemberMutual(std::string group, std::shared_ptr<const NeighbourMutual> mutual, int neighbours);
  std::vector<OutputDeclaration> outputs() const override { return {{"mutual_inductance", "H"}}; }
  std::vector<InputDeclaration> inputs() const override { return {{"deflection", true}}; }
  void compute_outputs(const Evaluation& evaluation) const override;

 private:
  std::shared_ptr<const NeighbourMutual> mutual_;
  int neighbours_;
};

}  // namespace tcpmsim
