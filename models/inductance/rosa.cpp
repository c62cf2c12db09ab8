#include "models/inductance/rosa.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "models/inductance/constants.h"
#include "models/inductance/solenoid.h"

namespace tcpmsim::inductance {

namespace {

// Inner sum of (2.10) for ring distance i (in pitches): the logarithm of the ratio of the
// geometric mean distance of two strips i pitches apart to i.
double rosa_inner_sum(int i) {
  if (i == 1) return 1.5 - 2.0 * std::numbers::ln2;  // sum of the telescoping series at i = 1
  const double x2 = 1.0 / (static_cast<double>(i) * i);
  double power = 1.0;
  double sum = 0.0;
  for (int j = 1; j < 1000; ++j) {
    power *= x2;
    const double term = (1.0 / (2 * j) + 1.0 / (2 * j + 2) - 2.0 / (2 * j + 1)) * power;
    sum += term;
    if (term < 1e-17 * sum) break;
  }
  return sum;
}

}  // namespace

double rosa_self_correction(double pitch, double wire_diameter) {
  return 1.25 - std::log(2.0 * pitch / wire_diameter);  // (2.9)
}

double rosa_mutual_correction_series(double turns) {
  if (!(turns >= 1.0)) throw std::domain_error("rosa_mutual_correction_series: needs N >= 1");
  double sum = 0.0;
  for (int i = 1; i < turns; ++i) sum += (turns - i) * rosa_inner_sum(i);
  return 2.0 / turns * sum;  // (2.10)
}

double rosa_mutual_correction_weaver(double turns) {
  const double n = turns;
  const double n2 = n * n;
  const double n3 = n2 * n;
  const double n5 = n3 * n2;
  const double n7 = n5 * n2;
  const double n9 = n7 * n2;
  return std::log(2.0 * std::numbers::pi) - 1.5 - std::log(n) / (6.0 * n) - 0.33084236 / n -
         1.0 / (120.0 * n3) + 1.0 / (504.0 * n5) - 0.0011923 / n7 + 0.0005068 / n9;
}

double rosa_inductance(const CoilGeometry& coil, RosaMutualCorrection method) {
  const double a = rosa_self_correction(coil.pitch(), coil.wire_diameter);
  const double b = method == RosaMutualCorrection::series
                       ? rosa_mutual_correction_series(coil.turns)
                       : rosa_mutual_correction_weaver(coil.turns);
  return nagaoka_inductance(coil) - mu0 * coil.radius * coil.turns * (a + b);  // (2.7), (2.8)
}

}  // namespace tcpmsim::inductance
