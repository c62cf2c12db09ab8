#include "models/laws/packing.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <stdexcept>

namespace tcpmsim {

int BundleCrossSection::coordination() const {
  return layout == PackingLayout::hexagonal ? 6 : 4;
}

namespace packing {

namespace {

struct LatticePoint {
  long ring_key;  // the squared distance in lattice units, scaled to an integer
  double angle;   // [0, 2 pi) from +x
  std::array<double, 2> centre;
  std::array<long, 2> index;  // (i, j)
};

// The lattice steps to the points one pitch away: the coordination shell.
std::vector<std::array<long, 2>> touching_steps(PackingLayout layout) {
  if (layout == PackingLayout::square) return {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
  return {{1, 0}, {-1, 0}, {0, 1}, {0, -1}, {1, -1}, {-1, 1}};
}

// Each member's touching members, ascending: the lattice points one step away that are members,
// found through a map of the members' lattice indices (linear in the count; comparing every pair
// of centres took minutes for a hundred thousand members).
std::vector<std::vector<int>> touching(PackingLayout layout,
                                       const std::vector<LatticePoint>& members) {
  std::map<std::array<long, 2>, int> member_at;
  for (std::size_t k = 0; k < members.size(); ++k)
    member_at.emplace(members[k].index, static_cast<int>(k));
  std::vector<std::vector<int>> neighbours(members.size());
  for (std::size_t k = 0; k < members.size(); ++k) {
    for (const auto& step : touching_steps(layout)) {
      const auto found =
          member_at.find({members[k].index[0] + step[0], members[k].index[1] + step[1]});
      if (found != member_at.end()) neighbours[k].push_back(found->second);
    }
    std::sort(neighbours[k].begin(), neighbours[k].end());
  }
  return neighbours;
}

// The lattice point (i, j) in pitches: hexagonal rows are shifted by half a pitch and sqrt(3)/2
// apart. Squared distances are integers (square) or multiples of 1/4 (hexagonal), so 4 d^2 is
// an exact key that groups each ring.
LatticePoint lattice_point(PackingLayout layout, long i, long j) {
  const bool hexagonal = layout == PackingLayout::hexagonal;
  const double x =
      hexagonal ? static_cast<double>(i) + 0.5 * static_cast<double>(j) : static_cast<double>(i);
  const double y =
      hexagonal ? 0.5 * std::sqrt(3.0) * static_cast<double>(j) : static_cast<double>(j);
  const long key = hexagonal ? (2 * i + j) * (2 * i + j) + 3 * j * j : 4 * (i * i + j * j);
  double angle = std::atan2(y, x);
  if (angle < 0.0) angle += 2.0 * std::numbers::pi;
  if (angle >= 2.0 * std::numbers::pi - 1e-12) angle = 0.0;
  return {key, angle, {x, y}, {i, j}};
}

}  // namespace

BundleCrossSection cross_section(PackingLayout layout, int count, double pitch) {
  if (count < 1 || !(pitch > 0.0))
    throw std::invalid_argument("a bundle needs at least one muscle and a positive pitch");
  const long reach = static_cast<long>(std::ceil(std::sqrt(static_cast<double>(count)))) + 2;
  std::vector<LatticePoint> points;
  for (long i = -2 * reach; i <= 2 * reach; ++i) {
    for (long j = -reach; j <= reach; ++j) points.push_back(lattice_point(layout, i, j));
  }
  std::sort(points.begin(), points.end(), [](const LatticePoint& a, const LatticePoint& b) {
    return a.ring_key != b.ring_key ? a.ring_key < b.ring_key : a.angle < b.angle;
  });
  BundleCrossSection section;
  section.layout = layout;
  section.pitch = pitch;
  for (int k = 0; k < count; ++k) {
    const auto& centre = points[static_cast<std::size_t>(k)].centre;
    section.centres.push_back({centre[0] * pitch, centre[1] * pitch});
  }
  points.resize(static_cast<std::size_t>(count));
  section.neighbours = touching(layout, points);
  return section;
}

double exposed_fraction(int neighbours, int coordination, double shielding) {
  return 1.0 - shielding * static_cast<double>(neighbours) / static_cast<double>(coordination);
}

}  // namespace packing

}  // namespace tcpmsim
