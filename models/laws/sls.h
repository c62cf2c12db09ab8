#pragma once

// The muscle's mechanics (thesis (7.5)-(7.6)): a standard linear solid (SLS) in parallel with
// the thermal force and an offset,  F = F_l + F_T + phi_0   (7.5).
//
// The SLS is a spring k1 in parallel with a Maxwell arm (spring k2 in series with a dashpot
// c). Its state is the dashpot extension x_d:
//     c dx_d/dt = k2 (x - x_d),     F_l = k1 x + k2 (x - x_d).
// Differentiating F_l gives the thesis' form
//     dF_l/dt = -(k2/c) F_l + (k1 k2 / c) x + (k1 + k2) dx/dt   (7.6)
// without needing dx/dt, so a step in imposed deflection is exact (an instantaneous elastic
// response of stiffness k1 + k2). Relaxation after a deflection step has tau = c/k2; creep
// under a force step has tau = c (k1 + k2) / (k1 k2).
//
// One law, one place: the plant (SlsMechanics), attached Maxwell arms (MaxwellBranch), the
// estimator (total_force, and DiscreteSls, its exact discretisation) and the
// describing-function linearisation all use these functions.
namespace tcpmsim {

struct SlsParameters {
  double k1 = 0.0;            // [N/m]
  double k2 = 0.0;            // [N/m]
  double damping = 0.0;       // c [N s/m]
  double force_offset = 0.0;  // phi_0 [N]
};

namespace sls {

// A Maxwell arm (a spring in series with a dashpot) stretched to x with the dashpot at x_d:
// its force k (x - x_d), and the rate at which the dashpot gives, dx_d/dt = (k/c) (x - x_d).
inline double arm_force(double stiffness, double deflection, double dashpot) {
  return stiffness * (deflection - dashpot);
}
inline double arm_rate(double stiffness, double damping, double deflection, double dashpot) {
  return stiffness / damping * (deflection - dashpot);
}

// F_l = k1 x + k2 (x - x_d)
inline double elastic_force(const SlsParameters& p, double deflection, double dashpot) {
  return p.k1 * deflection + arm_force(p.k2, deflection, dashpot);
}

// (7.5): F = F_l + F_T + phi_0
inline double total_force(const SlsParameters& p, double elastic_force, double thermal_force) {
  return elastic_force + thermal_force + p.force_offset;
}

// dx_d/dt = (k2/c) (x - x_d)
inline double dashpot_rate(const SlsParameters& p, double deflection, double dashpot) {
  return arm_rate(p.k2, p.damping, deflection, dashpot);
}

// (7.5) solved for x when F is imposed, with further terms S x + B attached in parallel
// (models/effects; none: S = B = 0): F = (k1 + k2 + S) x - k2 x_d + F_T + phi_0 + B.
inline double deflection_at_force(const SlsParameters& p, double force, double thermal_force,
                                  double dashpot, double attached_stiffness = 0.0,
                                  double attached_force = 0.0) {
  return (force - thermal_force - p.force_offset - attached_force + p.k2 * dashpot) /
         (p.k1 + p.k2 + attached_stiffness);
}

// At rest (every dashpot relaxed, x_d = x) under force F, the attached terms as they are at
// rest: F = (k1 + S) x + F_T + phi_0 + B.
inline double rest_deflection(const SlsParameters& p, double force, double thermal_force,
                              double attached_stiffness = 0.0, double attached_force = 0.0) {
  return (force - thermal_force - p.force_offset - attached_force) / (p.k1 + attached_stiffness);
}

// The thermal force that holds force F at deflection x with the dashpot relaxed.
inline double rest_thermal_force(const SlsParameters& p, double force, double deflection) {
  return force - p.k1 * deflection - p.force_offset;
}

// The linear model at an imposed (constant) force, in deviations: from deflection_at_force and
// dashpot_rate,
//     dx_d/dt = a_dd x_d + a_dT F_T,     x = c_xd x_d + c_xT F_T.
struct ForceModeLinearisation {
  double dashpot_from_dashpot;     // a_dd = -k1 k2 / (c (k1 + k2)) [1/s]
  double dashpot_from_thermal;     // a_dT = -k2 / (c (k1 + k2)) [m/(N s)]
  double deflection_from_dashpot;  // c_xd = k2 / (k1 + k2)
  double deflection_from_thermal;  // c_xT = -1 / (k1 + k2) [m/N]
};
ForceModeLinearisation linearise_at_force(const SlsParameters& p);

}  // namespace sls

// (7.6) driven by the sampled deflection x[k] and its backward difference v[k] = (x[k] - x[k-1])
// / T, discretised exactly for the velocity held over each sample interval (t_{k-1}, t_k].
//
// Derivation. x and dx/dt cannot both be held constant over an interval unless v = 0. Holding
// the velocity makes the deflection its integral, the straight line from x[k-1] to x[k]. With
// w = F_l - (k1 + k2) x, (7.6) loses its derivative term: dw/dt = -beta w - beta k2 x, with
// beta = k2/c. Integrating over the interval with x(t_{k-1} + s) = x[k-1] + v s:
//     w[k] = phi w[k-1] - k2 (1 - phi) x[k-1] - k2 v (T - (1 - phi) / beta),   phi = exp(-beta T),
// and back in F_l, with x[k-1] = x[k] - v T:
//     F_l[k] = phi F_l[k-1] + (1 - phi) k1 x[k] + (phi k1 T + (1 - phi) c) v[k].
// This is exact for any deflection that is piecewise linear between sample instants (a ramp
// gives F_l = k1 x + c v exactly), and the backward difference is the thesis' velocity
// estimate. The alternative of holding x[k] and v[k] as two independent inputs (a plain
// zero-order-hold c2d of (7.6) with input [x, dx/dt]) mixes a constant deflection with a
// non-zero velocity; it lags a steady ramp by k1 v T / 2 (0.27 mN at 1 mm/s, 20 Hz) and misses
// the plant at the sample instants by that much.
// reset() starts the branch at rest (dashpot relaxed): F_l = k1 x, as the plant's SlsMechanics.
class DiscreteSls {
 public:
  DiscreteSls(const SlsParameters& parameters, double period);
  void reset(double deflection) { value_ = k1_ * deflection; }
  // Any other state: F_l = sls::elastic_force(p, x, x_d).
  void set_elastic_force(double elastic_force) { value_ = elastic_force; }
  double advance(double deflection, double velocity) {
    return value_ = decay_ * value_ + deflection_gain_ * deflection + velocity_gain_ * velocity;
  }
  double value() const { return value_; }
  double decay() const { return decay_; }  // phi

 private:
  double k1_;
  double decay_;
  double deflection_gain_;  // (1 - phi) k1 [N/m]
  double velocity_gain_;    // phi k1 T + (1 - phi) c [N s/m]
  double value_ = 0.0;
};

}  // namespace tcpmsim
