#include "models/bundle/bundle_magnetics.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "models/inductance/parallel_coils.h"
#include "models/typical_values.h"

namespace tcpmsim {

namespace {

constexpr int kNodes = 25;          // Chebyshev nodes over [l0 / 4, 4 l0]
constexpr double kShortest = 0.25;  // of the rest length
constexpr double kLongest = 4.0;
constexpr double kTableTolerance = 1e-6;  // relative, between the nodes
// The most turns a coil may have: the table evaluates M at 2 kNodes - 1 lengths, each a sum of a
// ring integral per offset between rings, `turns` of them (as a spring's windings).
constexpr double kMaxTurns = 1e4;

// Node k of n on [a, b] (Chebyshev points of the first kind).
double chebyshev_node(int k, int n, double a, double b) {
  const double t = std::cos(std::numbers::pi * (k + 0.5) / n);
  return 0.5 * (a + b) + 0.5 * (b - a) * t;
}

// The barycentric weight of first-kind node k of n, (-1)^k sin((k + 1/2) pi / n).
double barycentric_weight(int k, int n) {
  return (k % 2 == 0 ? 1.0 : -1.0) * std::sin(std::numbers::pi * (k + 0.5) / n);
}

}  // namespace

// The barycentric interpolant through the values at the nodes.
double NeighbourMutual::interpolate(double u) const {
  double numerator = 0.0, denominator = 0.0;
  for (std::size_t k = 0; k < values_.size(); ++k) {
    if (u == nodes_[k]) return values_[k];
    const double weight = weights_[k] / (u - nodes_[k]);
    numerator += weight * values_[k];
    denominator += weight;
  }
  return numerator / denominator;
}

// The table runs in u = ln(l): M changes fastest at short lengths, where the rings crowd.
NeighbourMutual::NeighbourMutual(inductance::CoilGeometry at_rest, double separation)
    : at_rest_(at_rest),
      separation_(separation),
      shortest_(std::log(kShortest * at_rest.length)),
      longest_(std::log(kLongest * at_rest.length)) {
  const auto deflection_at = [&](double u) { return std::exp(u) - at_rest_.length; };
  for (int k = 0; k < kNodes; ++k) {
    nodes_.push_back(chebyshev_node(k, kNodes, shortest_, longest_));
    weights_.push_back(barycentric_weight(k, kNodes));
    values_.push_back(direct(deflection_at(nodes_.back())));
  }
  // Between the nodes, where an interpolant is worst.
  for (int k = 0; k + 1 < kNodes; ++k) {
    const double u =
        0.5 * (nodes_[static_cast<std::size_t>(k)] + nodes_[static_cast<std::size_t>(k + 1)]);
    const double exact = direct(deflection_at(u));
    table_error_ =
        std::max(table_error_, std::abs((*this)(deflection_at(u)) - exact) / std::abs(exact));
  }
  if (!(table_error_ <= kTableTolerance))
    throw std::domain_error("the table of M(x) is off by " + std::to_string(table_error_) +
                            " between its nodes");
}

std::shared_ptr<const NeighbourMutual> NeighbourMutual::from_config(const ConfigNode& node,
                                                                    double separation) {
  node.declare({"coil"});
  const ConfigNode coil = node.at("coil");
  coil.declare({"radius", "turns", "length", "wire_diameter"});
  inductance::CoilGeometry geometry;
  geometry.radius = coil.quantity("radius", "m", typical::coil_radius(ValueCheck::positive()));
  geometry.turns = coil.number(
      "turns",
      ValueCheck::count(kMaxTurns, "the table of M(x) sums an integral per ring offset at " +
                                       std::to_string(2 * kNodes - 1) + " lengths"));
  geometry.length = coil.quantity("length", "m", typical::muscle_length(ValueCheck::positive()));
  geometry.wire_diameter =
      coil.quantity("wire_diameter", "m", typical::wire_diameter(ValueCheck::positive()));
  if (!(separation > 2.0 * geometry.radius + geometry.wire_diameter)) {
    coil.at("radius").fail(
        "neighbouring coils at the packing pitch would overlap: the pitch must "
        "exceed the coil's outer diameter 2 r + delta");
  }
  return std::make_shared<NeighbourMutual>(geometry, separation);
}

double NeighbourMutual::direct(double deflection) const {
  inductance::CoilGeometry coil = at_rest_;
  coil.length = at_rest_.length + deflection;
  return inductance::parallel_coils_mutual_inductance(coil, separation_);
}

double NeighbourMutual::operator()(double deflection) const {
  // Held at the table's ends: this runs inside the right-hand side, which must neither throw
  // nor take milliseconds (a coil a quarter or four times its rest length is far outside any
  // muscle's stroke).
  const double length = at_rest_.length + deflection;
  const double u = length > 0.0 ? std::clamp(std::log(length), shortest_, longest_) : shortest_;
  return interpolate(u);
}

MemberMutual::MemberMutual(std::string group, std::shared_ptr<const NeighbourMutual> mutual,
                           int neighbours)
    : Component(std::move(group), "member_mutual"),
      mutual_(std::move(mutual)),
      neighbours_(neighbours) {}

void MemberMutual::compute_outputs(const Evaluation& evaluation) const {
  set_output(evaluation, 0, neighbours_ * (*mutual_)(input(evaluation, 0)));
}

}  // namespace tcpmsim
