#pragma once

#include <span>

#include "models/laws/impedance.h"

namespace tcpmsim::inductance {

// The fitted spring model (2.14), L = alpha / l + beta, with l the coil length. It is the TCPM
// law (6.3)/(7.3) with lambda_l = alpha, lambda_x = 0 (deflection measured as the length
// itself), lambda_T = 0 and lambda_0 = beta, so it is held as an InductanceLaw.
class SpringInductanceFit {
 public:
  SpringInductanceFit() = default;
  SpringInductanceFit(double alpha, double beta);

  // Through two calibration points (l1, L1), (l2, L2) with l1 != l2 (section 2.2.7).
  static SpringInductanceFit two_point(double length1, double inductance1, double length2,
                                       double inductance2);
  // Least squares of L against 1/l over all points (at least two distinct lengths).
  static SpringInductanceFit least_squares(std::span<const double> lengths,
                                           std::span<const double> inductances);

  double alpha() const { return law_.lambda_l; }  // [H*m]
  double beta() const { return law_.lambda_0; }   // [H]
  double inductance(double length) const;         // (2.14)
  double length(double inductance) const;         // l = alpha / (L - beta)
  const InductanceLaw& law() const { return law_; }

 private:
  InductanceLaw law_;
};

}  // namespace tcpmsim::inductance
