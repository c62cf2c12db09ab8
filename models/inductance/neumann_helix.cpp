#include "models/inductance/neumann_helix.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "models/inductance/constants.h"
#include "models/inductance/loop_mutual.h"

namespace tcpmsim::inductance {

namespace {

struct Helix {
  double radius;
  double wire_length;  // Lw
  double k;            // cos(psi) / r: turning angle per unit arc length
  double sin_psi;
  double cos2_psi;
  double theta0;  // angular offset of filament 2 (it sits at -theta0)
  double y0;      // axial offset of filament 2

  // F(phi) of the header: tangent dot product over distance.
  double f(double phi) const {
    // 1 - cos(angle) as 2 sin^2(angle/2): no cancellation where the filaments are close.
    const double half_sine = std::sin(0.5 * (k * phi + theta0));
    const double one_minus_cos = 2.0 * half_sine * half_sine;
    const double axial = phi * sin_psi - y0;
    return (1.0 - cos2_psi * one_minus_cos) /
           std::sqrt(2.0 * radius * radius * one_minus_cos + axial * axial);
  }
  double integrand(double phi) const { return (wire_length - phi) * (f(phi) + f(-phi)); }
};

// Angle theta0 >= 0 with 2 r^2 (1 - cos theta0) + (r theta0 cot psi)^2 = g^2: the offset of
// length g perpendicular to the wire in the developed winding surface. The left side increases
// monotonically on [0, pi]; Newton from Weaver's small-angle start, kept inside a bracket.
double offset_angle(double radius, double gmd, double cot_psi) {
  const double r2 = radius * radius;
  const auto residual = [&](double t) {
    const double axial = radius * t * cot_psi;
    const double half_sine = std::sin(0.5 * t);
    return 4.0 * r2 * half_sine * half_sine + axial * axial - gmd * gmd;
  };
  double low = 0.0, high = std::numbers::pi;
  if (residual(high) < 0.0) {
    throw std::domain_error("neumann_helix_inductance: wire gmd exceeds the coil diameter");
  }
  double t = gmd / std::sqrt(r2 * (1.0 + cot_psi * cot_psi));  // small-angle solution
  for (int iteration = 0; iteration < 100; ++iteration) {
    const double value = residual(t);
    if (value > 0.0)
      high = t;
    else
      low = t;
    const double slope = 2.0 * r2 * std::sin(t) + 2.0 * r2 * cot_psi * cot_psi * t;
    double next = slope > 0.0 ? t - value / slope : 0.5 * (low + high);
    if (!(next > low && next < high)) next = 0.5 * (low + high);
    if (std::abs(next - t) <= 1e-15 * std::max(t, 1e-300)) return next;
    t = next;
  }
  return t;
}

// Adaptive Simpson on [a, b] with absolute tolerance `tolerance`, Richardson-corrected.
// Iterative with an explicit stack; an interval is halved at most kMaxDepth times, and every
// evaluation of f is counted against `budget` (refinement stops when it runs out).
template <typename F>
double adaptive_simpson(const F& f, double a, double b, double tolerance, long& budget) {
  constexpr int kMaxDepth = 40;
  struct Interval {
    double a, b, fa, fm, fb, whole, tolerance;
    int depth;
  };
  Interval stack[kMaxDepth + 2];
  int top = 0;
  const double fa = f(a), fb = f(b), fm = f(0.5 * (a + b));
  budget -= 3;
  stack[top++] = {a, b, fa, fm, fb, (b - a) / 6.0 * (fa + 4.0 * fm + fb), tolerance, 0};
  double total = 0.0;
  while (top > 0) {
    const Interval interval = stack[--top];
    const double m = 0.5 * (interval.a + interval.b);
    const double left_mid = f(0.5 * (interval.a + m));
    const double right_mid = f(0.5 * (m + interval.b));
    budget -= 2;
    const double half = 0.5 * (interval.b - interval.a);
    const double left = half / 6.0 * (interval.fa + 4.0 * left_mid + interval.fm);
    const double right = half / 6.0 * (interval.fm + 4.0 * right_mid + interval.fb);
    const double difference = left + right - interval.whole;
    // Converged, or down to rounding (the integrand carries ~1e-16 relative noise), or out of
    // depth or budget.
    const double rounding =
        8.0 * std::numeric_limits<double>::epsilon() * (std::abs(left) + std::abs(right));
    if (std::abs(difference) <= std::max(15.0 * interval.tolerance, rounding) ||
        interval.depth >= kMaxDepth || budget <= 0) {
      total += left + right + difference / 15.0;
      continue;
    }
    const double child_tolerance = 0.5 * interval.tolerance;
    stack[top++] = {m,           interval.b, interval.fm,     right_mid,
                    interval.fb, right,      child_tolerance, interval.depth + 1};
    stack[top++] = {interval.a,  m,    interval.fa,     left_mid,
                    interval.fm, left, child_tolerance, interval.depth + 1};
  }
  return total;
}

// Composite Simpson of |f| on [a, b] with 16 intervals: the scale the tolerance refers to.
template <typename F>
double absolute_scale(const F& f, double a, double b) {
  constexpr int kIntervals = 16;
  const double h = (b - a) / kIntervals;
  double sum = std::abs(f(a)) + std::abs(f(b));
  for (int i = 1; i < kIntervals; ++i) sum += (i % 2 ? 4.0 : 2.0) * std::abs(f(a + i * h));
  return sum * h / 3.0;
}

constexpr long kEvaluationBudget = 50'000'000;  // integrand pairs F(phi), F(-phi); ~2 s

}  // namespace

double neumann_helix_inductance(const CoilGeometry& coil, double relative_tolerance) {
  if (!(coil.radius > 0.0) || !(coil.length > 0.0) || !(coil.turns > 0.0) ||
      !(coil.wire_diameter > 0.0)) {
    throw std::domain_error("neumann_helix_inductance: geometry must be positive");
  }
  if (!(relative_tolerance > 0.0)) {
    throw std::domain_error("neumann_helix_inductance: tolerance must be positive");
  }
  const double r = coil.radius;
  const double psi = std::atan(coil.length / (2.0 * std::numbers::pi * r * coil.turns));
  const double gmd = wire_gmd(coil.wire_diameter);
  const double cot_psi = std::cos(psi) / std::sin(psi);
  const double theta0 = offset_angle(r, gmd, cot_psi);

  Helix helix;
  helix.radius = r;
  helix.wire_length = 2.0 * std::numbers::pi * coil.turns * r / std::cos(psi);
  helix.k = std::cos(psi) / r;
  helix.sin_psi = std::sin(psi);
  helix.cos2_psi = std::cos(psi) * std::cos(psi);
  helix.theta0 = theta0;
  helix.y0 = r * theta0 * cot_psi;

  // Panel edges. F(phi) and F(-phi) peak where the two filaments come closest: at phi = 0
  // over a width ~g, and near every whole turn phi = j Lt over a width ~j p. Every turn of wire
  // is one interval, graded geometrically towards both of its ends (g, 2g, 4g, ... from the
  // start of the wire; p, 2p, 4p, ... elsewhere) so that each peak sits at a panel edge.
  const double wire = helix.wire_length;
  const double turn = 2.0 * std::numbers::pi * r / std::cos(psi);  // Lt
  const double pitch = coil.length / coil.turns;
  std::vector<double> edges{0.0};
  for (long j = 0; static_cast<double>(j) * turn < wire * (1.0 - 1e-12); ++j) {
    const double start = static_cast<double>(j) * turn;
    const double end = std::min(start + turn, wire);
    const double middle = 0.5 * (start + end);
    for (double width = start == 0.0 ? gmd : pitch; start + width < middle; width *= 2.0) {
      edges.push_back(start + width);
    }
    edges.push_back(middle);
    std::vector<double> right;
    for (double width = pitch; end - width > middle; width *= 2.0) right.push_back(end - width);
    edges.insert(edges.end(), right.rbegin(), right.rend());
    edges.push_back(end);
  }
  const auto integrand = [&helix](double phi) { return helix.integrand(phi); };
  double scale = 0.0;
  for (std::size_t i = 0; i + 1 < edges.size(); ++i) {
    scale += absolute_scale(integrand, edges[i], edges[i + 1]);
  }
  // The tolerance is shared among the panels in proportion to their length (at least 1e-3 of
  // the wire each, so that the short panels at the peaks are not asked for the impossible).
  double shares = 0.0;
  for (std::size_t i = 0; i + 1 < edges.size(); ++i) {
    shares += std::max((edges[i + 1] - edges[i]) / wire, 1e-3);
  }
  long budget = kEvaluationBudget;
  double integral = 0.0;
  for (std::size_t i = 0; i + 1 < edges.size(); ++i) {
    const double share = std::max((edges[i + 1] - edges[i]) / wire, 1e-3) / shares;
    integral += adaptive_simpson(integrand, edges[i], edges[i + 1],
                                 relative_tolerance * scale * share, budget);
  }
  if (budget <= 0) {
    throw std::runtime_error("neumann_helix_inductance: tolerance " +
                             std::to_string(relative_tolerance) + " not reached within " +
                             std::to_string(kEvaluationBudget) + " integrand evaluations");
  }
  return mu0 / (4.0 * std::numbers::pi) * integral;  // (2.1)
}

}  // namespace tcpmsim::inductance
