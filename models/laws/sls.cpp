#include "models/laws/sls.h"

#include <cmath>
#include <stdexcept>

namespace tcpmsim {

sls::ForceModeLinearisation sls::linearise_at_force(const SlsParameters& p) {
  const double k1 = p.k1, k2 = p.k2, c = p.damping;
  return {-k1 * k2 / (c * (k1 + k2)), -k2 / (c * (k1 + k2)), k2 / (k1 + k2), -1.0 / (k1 + k2)};
}

DiscreteSls::DiscreteSls(const SlsParameters& parameters, double period) : k1_(parameters.k1) {
  if (!(parameters.damping > 0.0)) throw std::invalid_argument("SLS: damping must be positive");
  const double beta = parameters.k2 / parameters.damping;  // relaxation rate k2/c
  const double one_minus_decay = -std::expm1(-beta * period);
  decay_ = 1.0 - one_minus_decay;
  deflection_gain_ = one_minus_decay * parameters.k1;
  velocity_gain_ = decay_ * parameters.k1 * period + one_minus_decay * parameters.damping;
}

}  // namespace tcpmsim
