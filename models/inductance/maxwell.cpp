#include "models/inductance/maxwell.h"

#include <cmath>

#include "models/inductance/loop_mutual.h"

namespace tcpmsim::inductance {

double maxwell_ring_stack(double radius, double self_distance, int rings, double pitch) {
  double mutual = 0.0;
  for (int i = 1; i < rings; ++i) mutual += (rings - i) * loop_mutual_inductance(radius, i * pitch);
  return rings * loop_mutual_inductance(radius, self_distance) + 2.0 * mutual;  // (2.13)
}

double maxwell_inductance(const CoilGeometry& coil) {
  // (2.13): mutual terms over round(N) rings, the self term with the non-integer N.
  const int rings = static_cast<int>(std::lround(coil.turns));
  const double self_distance = wire_gmd(coil.wire_diameter);
  return maxwell_ring_stack(coil.radius, self_distance, rings, coil.pitch()) +
         (coil.turns - rings) * loop_mutual_inductance(coil.radius, self_distance);
}

double maxwell_positions(double radius, double self_distance, std::span<const double> positions) {
  double mutual = 0.0;
  for (std::size_t i = 0; i < positions.size(); ++i) {
    for (std::size_t j = i + 1; j < positions.size(); ++j) {
      mutual += loop_mutual_inductance(radius, std::abs(positions[i] - positions[j]));
    }
  }
  // (4.11) with M_ij = M_ji: the diagonal plus twice the upper triangle.
  return static_cast<double>(positions.size()) * loop_mutual_inductance(radius, self_distance) +
         2.0 * mutual;
}

}  // namespace tcpmsim::inductance
