#include "models/inductance/spring_inductance_fit.h"

#include <stdexcept>

namespace tcpmsim::inductance {

SpringInductanceFit::SpringInductanceFit(double alpha, double beta) {
  law_.lambda_l = alpha;
  law_.lambda_x = 0.0;
  law_.lambda_T = 0.0;
  law_.lambda_0 = beta;
}

SpringInductanceFit SpringInductanceFit::two_point(double length1, double inductance1,
                                                   double length2, double inductance2) {
  const double u1 = 1.0 / length1, u2 = 1.0 / length2;
  if (!(u1 != u2)) throw std::invalid_argument("two-point fit needs two different lengths");
  const double alpha = (inductance1 - inductance2) / (u1 - u2);
  return {alpha, inductance1 - alpha * u1};  // (2.14) through both points
}

SpringInductanceFit SpringInductanceFit::least_squares(std::span<const double> lengths,
                                                       std::span<const double> inductances) {
  if (lengths.size() != inductances.size() || lengths.size() < 2) {
    throw std::invalid_argument("least-squares fit needs at least two (length, L) pairs");
  }
  const double n = static_cast<double>(lengths.size());
  double mean_u = 0.0, mean_l = 0.0;
  for (std::size_t i = 0; i < lengths.size(); ++i) {
    mean_u += 1.0 / lengths[i];
    mean_l += inductances[i];
  }
  mean_u /= n;
  mean_l /= n;
  double suu = 0.0, sul = 0.0;  // centred sums: no cancellation of large means
  for (std::size_t i = 0; i < lengths.size(); ++i) {
    const double du = 1.0 / lengths[i] - mean_u;
    suu += du * du;
    sul += du * (inductances[i] - mean_l);
  }
  if (!(suu > 0.0)) throw std::invalid_argument("least-squares fit needs distinct lengths");
  const double alpha = sul / suu;
  return {alpha, mean_l - alpha * mean_u};
}

double SpringInductanceFit::inductance(double length) const {
  return law_(length, law_.reference_temperature);  // (2.14) via (6.3) with lambda_x = 0
}

double SpringInductanceFit::length(double inductance) const {
  return law_.deflection(inductance, law_.reference_temperature);  // (7.4): alpha / (L - beta)
}

}  // namespace tcpmsim::inductance
