// One law, one place: the estimator's exact discretisations and the linearisation used by the
// describing-function analysis are derived from the same law functions the plant integrates
// (models/laws/). Here each is set against the plant law itself, integrated finely.
#include <catch2/catch.hpp>

#include <cmath>
#include <functional>

#include "models/laws/sls.h"
#include "models/laws/thermal_force.h"
#include "tests/support/test_support.h"

using namespace tcpmsim;
using namespace tcpmsim::testing;

namespace {

// y' = f(s, y) over [0, duration] by classical Runge-Kutta in `steps` steps, the increments summed
// with Kahan's compensation so that rounding does not accumulate over the steps. For these
// linear laws the truncation error is about (h lambda)^5 / 120 per step: below 1e-18 here.
double integrate(const std::function<double(double, double)>& f, double y, double duration,
                 int steps = 4000) {
  const double h = duration / steps;
  double compensation = 0.0;
  for (int i = 0; i < steps; ++i) {
    const double s = i * h;
    const double k1 = f(s, y), k2 = f(s + h / 2, y + h / 2 * k1), k3 = f(s + h / 2, y + h / 2 * k2),
                 k4 = f(s + h, y + h * k3);
    const double increment = h / 6 * (k1 + 2 * k2 + 2 * k3 + k4) - compensation;
    const double sum = y + increment;
    compensation = (sum - y) - increment;
    y = sum;
  }
  return y;
}

constexpr double kPeriod = 0.05;  // the Muscle Drive's 20 Hz

}  // namespace

TEST_CASE(
    "Over one sample the estimator's discrete SLS equals the plant's SLS law, from any state") {
  // Thesis Table 7.2, a fast arm (k2/c T = 1.25) and a stiff slow one; the deflection moves in a
  // straight line over the sample (the velocity the estimator holds), the dashpot starts off
  // its rest position.
  const SlsParameters table_7_2 = thesis_estimator_parameters().mechanics;
  for (const SlsParameters& p :
       {table_7_2, SlsParameters{10.8, 100.0, 4.0, 0.1}, SlsParameters{50.0, 2.0, 40.0, -0.2}}) {
    for (double velocity : {0.0, 1e-3, -7e-3}) {
      const double x0 = 18e-3, dashpot0 = 15e-3, x1 = x0 + velocity * kPeriod;
      auto deflection = [&](double s) { return x0 + velocity * s; };
      const double dashpot1 = integrate(
          [&](double s, double dashpot) { return sls::dashpot_rate(p, deflection(s), dashpot); },
          dashpot0, kPeriod);
      const double plant = sls::elastic_force(p, x1, dashpot1);
      DiscreteSls discrete(p, kPeriod);
      discrete.set_elastic_force(sls::elastic_force(p, x0, dashpot0));
      INFO("k1 " << p.k1 << " k2 " << p.k2 << " c " << p.damping << " v " << velocity);
      CHECK(discrete.advance(x1, velocity) == Approx(plant).epsilon(1e-13));
    }
  }
}

TEST_CASE("Over one sample the estimator's discrete (7.1) equals the plant's (7.1)") {
  const auto p = thesis_estimator_parameters();
  for (double cooling : {p.cooling_rate, 5.0, 1e-6}) {
    for (double power : {0.0, 0.1, 3.12}) {
      const double start = 0.21;  // N, not at rest
      const double plant = integrate(
          [&](double, double f) { return thermal_force::rate(p.heating_gain, cooling, f, power); },
          start, kPeriod);
      DiscreteThermalForce discrete(p.heating_gain, cooling, kPeriod);
      discrete.reset(start);
      INFO("kappa_c " << cooling << " P " << power);
      CHECK(discrete.advance(power) == Approx(plant).epsilon(1e-13));
    }
  }
}

TEST_CASE("The SLS linearisation at imposed force is the plant law's own derivative") {
  // The law is linear, so a central difference of the plant functions is exact to rounding.
  const SlsParameters p = thesis_estimator_parameters().mechanics;
  const auto lin = sls::linearise_at_force(p);
  const double force = 0.4, thermal = 0.1, dashpot = 20e-3, h_dashpot = 1e-6, h_thermal = 1e-6;
  auto rate = [&](double thermal_force, double x_d) {
    return sls::dashpot_rate(p, sls::deflection_at_force(p, force, thermal_force, x_d), x_d);
  };
  auto deflection = [&](double thermal_force, double x_d) {
    return sls::deflection_at_force(p, force, thermal_force, x_d);
  };
  CHECK(lin.dashpot_from_dashpot ==
        Approx((rate(thermal, dashpot + h_dashpot) - rate(thermal, dashpot - h_dashpot)) /
               (2 * h_dashpot))
            .epsilon(1e-8));
  CHECK(lin.dashpot_from_thermal ==
        Approx((rate(thermal + h_thermal, dashpot) - rate(thermal - h_thermal, dashpot)) /
               (2 * h_thermal))
            .epsilon(1e-8));
  CHECK(lin.deflection_from_dashpot == Approx((deflection(thermal, dashpot + h_dashpot) -
                                               deflection(thermal, dashpot - h_dashpot)) /
                                              (2 * h_dashpot))
                                           .epsilon(1e-8));
  CHECK(lin.deflection_from_thermal == Approx((deflection(thermal + h_thermal, dashpot) -
                                               deflection(thermal - h_thermal, dashpot)) /
                                              (2 * h_thermal))
                                           .epsilon(1e-8));
  // And its creep time constant is the SLS's c (k1 + k2) / (k1 k2); the other entries written
  // out from (7.5)-(7.6) by hand, independently of the plant functions.
  CHECK(-1.0 / lin.dashpot_from_dashpot == Approx(p.damping * (p.k1 + p.k2) / (p.k1 * p.k2)));
  CHECK(lin.deflection_from_dashpot == Approx(p.k2 / (p.k1 + p.k2)).epsilon(1e-14));
  CHECK(lin.deflection_from_thermal == Approx(-1.0 / (p.k1 + p.k2)).epsilon(1e-14));
  CHECK(lin.dashpot_from_thermal == Approx(-p.k2 / (p.damping * (p.k1 + p.k2))).epsilon(1e-14));
}

TEST_CASE("The equilibrium power holds the muscle still: (7.1) and (7.5) at rest") {
  const auto p = thesis_estimator_parameters();
  const double force = 0.40, deflection = 20e-3;
  const double thermal = sls::rest_thermal_force(p.mechanics, force, deflection);
  const double power = thermal_force::equilibrium_power(p.heating_gain, p.cooling_rate, thermal);
  CHECK(thermal_force::rate(p.heating_gain, p.cooling_rate, thermal, power) ==
        Approx(0.0).margin(1e-15));
  CHECK(sls::total_force(p.mechanics, sls::elastic_force(p.mechanics, deflection, deflection),
                         thermal) == Approx(force).epsilon(1e-15));
}
