#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace tcpmsim::inductance {

// Maxwell's summation (4.11) over arbitrary ring positions, fast enough to evaluate at every
// output sample of a lumped-mass spring whose N ~ 25..52 gaps all differ.
//
// The loop mutual inductance M(h) of (2.11) is tabulated at construction over
// [min_distance, max_distance] as piecewise Chebyshev interpolants (degree 9) on segments that
// split every binary octave of h into 8 equal parts. A segment is found from the bits of h
// (exponent and 3 leading mantissa bits), so a lookup is a shift, a subtraction and a 10-term
// Horner sum; no logarithm, no search. The closest singularity of M(h) (the logarithm at
// h = 0) lies at least 16 half-widths from every segment's centre, so the interpolants converge
// to rounding: construction measures the table against the direct formula between the nodes of
// every segment and reports the largest relative deviation as table_error() (~4e-13, the
// accuracy of the direct formula itself, which rests on libstdc++'s elliptic integrals).
// Distances outside the table fall back to the direct formula, so results are always right.
//
// Evaluation allocates nothing and uses M_ij = M_ji (the upper triangle only); uniform spacing
// needs only the N - 1 distinct distances (2.13).
class MaxwellEvaluator {
 public:
  static constexpr int kDegree = 9;
  static constexpr int kSubdivisionBits = 3;  // 8 segments per octave of h

  // radius: coil radius r [m]; self_distance: the self term's distance, usually wire_gmd(delta);
  // [min_distance, max_distance]: the range of ring distances to tabulate [m].
  MaxwellEvaluator(double radius, double self_distance, double min_distance, double max_distance);

  // M(h) of (2.11) [H]; h must be positive.
  double mutual(double distance) const noexcept;
  // (4.11): sum_i sum_j M(|xi_i - xi_j|) with M(g) on the diagonal [H]. Positions in any order.
  double inductance(std::span<const double> positions) const noexcept;
  // (2.13): `rings` rings at equal pitch [H].
  double inductance_uniform(int rings, double pitch) const noexcept;

  double radius() const { return radius_; }
  double self_term() const { return self_term_; }  // M(g) [H]
  double table_min_distance() const { return table_min_; }
  double table_max_distance() const { return table_max_; }
  std::size_t segments() const { return segments_.size(); }
  // Largest relative deviation from loop_mutual_inductance found at construction.
  double table_error() const { return table_error_; }

 private:
  struct Segment {
    double centre = 0.0;
    double inverse_half_width = 0.0;
    std::array<double, kDegree + 1> coefficients{};  // monomials in t = (h - centre)/half width
  };
  static std::uint64_t key_of(double distance) noexcept;
  double direct(double distance) const noexcept;

  double radius_;
  double self_term_;
  double table_min_ = 0.0;
  double table_max_ = 0.0;
  std::uint64_t first_key_ = 0;
  std::vector<Segment> segments_;
  double table_error_ = 0.0;
};

}  // namespace tcpmsim::inductance
