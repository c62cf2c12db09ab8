#pragma once

#include <array>
#include <vector>

namespace tcpmsim {

// How the muscles of a bundle sit side by side in its cross-section.
enum class PackingLayout { hexagonal, square };

// The cross-section of a bundle of `count` parallel muscles on a lattice of spacing `pitch`:
// the lattice points nearest the centre, taken ring by ring (1, 7, 19, 37, ... fill hexagonal
// rings; 1, 5, 9, 13, 21, 25, ... square ones; a partial ring fills by angle from the +x axis),
// and which of them touch (centres one pitch apart).
struct BundleCrossSection {
  PackingLayout layout = PackingLayout::hexagonal;
  double pitch = 0.0;                          // [m] between touching centres
  std::vector<std::array<double, 2>> centres;  // [m], the centre of the bundle at 0
  std::vector<std::vector<int>> neighbours;    // per muscle, the touching ones, ascending
  int coordination() const;                    // neighbours of an inner muscle: 6 or 4
};

namespace packing {

BundleCrossSection cross_section(PackingLayout layout, int count, double pitch);

// The share of a muscle's free-air convective conductance it keeps among `neighbours`: each
// neighbour blocks `shielding` / coordination of its surface, so that an inner muscle keeps
// 1 - shielding and a lone one all of it.
double exposed_fraction(int neighbours, int coordination, double shielding);

}  // namespace packing

}  // namespace tcpmsim
