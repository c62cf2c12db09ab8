#include "analysis/published_rosa.h"

#include <cmath>
#include <numbers>

#include "models/inductance/constants.h"
#include "models/inductance/rosa.h"
#include "models/inductance/solenoid.h"

namespace tcpmsim::analysis {

double published_rosa_nagaoka_coefficient(double diameter_over_length) {
  const double u = diameter_over_length;
  const double uu = u * u;
  const double m = uu / (1.0 + uu);  // k^2
  const double m2 = 4.0 * std::sqrt(1.0 + uu);
  const double c = 1.0 - std::sqrt(1.0 - m);  // a - b with a = 1, b = k'
  double cs = c * c / 2.0 + m;
  // (the AGM loop would refine cs here; it runs zero times)
  cs /= 2.0;
  const double k = std::numbers::pi / 2.0;  // pi / (a + a) with a = 1
  const double k_minus_e = k * cs;
  const double e = k * (1.0 - cs);
  return 1.0 / (3.0 * std::numbers::pi) * (m2 / uu * k_minus_e + m2 * e - 4.0 * u);
}

double published_rosa_inductance(const inductance::CoilGeometry& coil) {
  using namespace inductance;
  const double sheet = basic_solenoid_inductance(coil) *
                       published_rosa_nagaoka_coefficient(coil.diameter() / coil.length);
  const double a = rosa_self_correction(coil.pitch(), coil.wire_diameter);
  const double b = rosa_mutual_correction_weaver(coil.turns);
  return sheet - mu0 * coil.radius * coil.turns * (a + b);
}

}  // namespace tcpmsim::analysis
