// Coil impedance laws (6.3)-(6.5), (7.3)-(7.4) and the static inversion (6.6)-(6.8), against
// the thesis' published parameters (Table 6.4) and ranges (Table 6.2).
#include <catch2/catch.hpp>

#include <cmath>

#include "models/laws/pwm_supply.h"
#include "models/static_self_sensing.h"

using namespace tcpmsim;

namespace {
constexpr double kZeroCelsius = 273.15;

// Table 6.4, converted to SI.
InductanceLaw table_6_4_inductance() {
  InductanceLaw law;
  law.lambda_l = 107.429e-6 * 1e-3;  // uH mm -> H m
  law.lambda_x = 0.061;              // l0 = 61 mm rest length
  law.lambda_T = 0.008e-6;           // uH/degC -> H/K
  law.lambda_0 = 2.670e-6;
  law.reference_temperature = kZeroCelsius;
  return law;
}

ResistanceLaw table_6_4_resistance() {
  return {-0.005e3, 0.030, 8.717, kZeroCelsius};
}
}  // namespace

TEST_CASE("Static self-sensing recovers (x, T) from (L, R) over the Table 6.2 ranges") {
  const auto inductance = table_6_4_inductance();
  const auto resistance = table_6_4_resistance();
  double worst_x = 0.0, worst_T = 0.0;
  for (double x_mm = 2.0; x_mm <= 30.0; x_mm += 0.5) {
    for (double T_c = 50.0; T_c <= 110.0; T_c += 2.5) {
      const double x = x_mm * 1e-3, T = T_c + kZeroCelsius;
      const auto recovered =
          invert_impedance(inductance, resistance, inductance(x, T), resistance(x, T));
      worst_x = std::max(worst_x, std::abs(recovered.deflection - x));
      worst_T = std::max(worst_T, std::abs(recovered.temperature - T));
    }
  }
  INFO("worst errors: " << worst_x << " m, " << worst_T << " K");
  CHECK(worst_x < 1e-12);
  CHECK(worst_T < 1e-9);
}

TEST_CASE("The Table 6.4 inductance law spans the Table 6.2 inductance range") {
  // Published: L in [4.254, 5.261] uH for x in [2, 30] mm and T in [50, 110] degC. The
  // extremes are at (30 mm, 50 degC) and (2 mm, 110 degC); parameters are printed to 3 decimals.
  const auto law = table_6_4_inductance();
  CHECK(law(0.030, 50 + kZeroCelsius) * 1e6 == Approx(4.254).margin(0.01));
  CHECK(law(0.002, 110 + kZeroCelsius) * 1e6 == Approx(5.261).margin(0.01));
}

TEST_CASE("The Table 6.4 resistance law meets the Table 6.2 range where its printed digits allow") {
  // Published: R in [10.091, 12.083] ohm over x in [2, 30] mm and T in [50, 110] degC. Each
  // printed parameter (rho_x = -0.005 ohm/mm, rho_T = 0.030 ohm/degC, rho_0 = 8.717 ohm) is
  // exact to half a unit of its last digit, so at (x, T) the law is known to within
  // 0.0005 ohm/mm x + 0.0005 ohm/degC T + 0.0005 ohm.
  const auto law = table_6_4_resistance();
  const auto digits = [](double x_mm, double T_c) { return 0.0005 * (x_mm + T_c + 1.0); };
  // The low end, (30 mm, 50 degC): -0.150 + 1.500 + 8.717 = 10.067 ohm, 0.024 below the
  // table, within the 0.0405 ohm the digits allow.
  CHECK(law(0.030, 50 + kZeroCelsius) == Approx(10.091).margin(digits(30, 50)));
  // The high end, (2 mm, 110 degC): -0.010 + 3.300 + 8.717 = 12.007 ohm, 0.076 below the table's
  // 12.083, more than the 0.0565 ohm the digits allow: Table 6.2's range is the measured one, not
  // (6.5)'s. Pinned, so that a change to the law shows here.
  const double high_end_gap = 12.083 - law(0.002, 110 + kZeroCelsius);
  CHECK(high_end_gap > digits(2, 110));
  CHECK(high_end_gap == Approx(0.076).margin(1e-9));
}

TEST_CASE("The printed (6.6) pairs T with the wrong root: with +sqrt(D) it does not round-trip") {
  // (6.6) as printed: T = (R lT + L rT - lT r0 - l0 rT + lT rx l0 + sqrt(D)) / (2 lT rT), in
  // the thesis' units (uH, ohm, mm, degC).
  const double lambda_l = 107.429, lambda_T = 0.008, lambda_0 = 2.670, l0 = 61.0;
  const double rho_x = -0.005, rho_T = 0.030, rho_0 = 8.717;
  const double x = 16.0, T = 80.0;
  const double L = lambda_l / (x + l0) + lambda_T * T + lambda_0;
  const double R = rho_x * x + rho_T * T + rho_0;
  const double D = std::pow(L * rho_T - R * lambda_T - lambda_T * rho_x * l0 + lambda_T * rho_0 -
                                lambda_0 * rho_T,
                            2) +
                   4 * lambda_l * lambda_T * rho_x * rho_T;
  const double common =
      R * lambda_T + L * rho_T - lambda_T * rho_0 - lambda_0 * rho_T + lambda_T * rho_x * l0;
  const double printed = (common + std::sqrt(D)) / (2 * lambda_T * rho_T);
  const double corrected = (common - std::sqrt(D)) / (2 * lambda_T * rho_T);
  CHECK(std::abs(printed - T) > 100.0);
  CHECK(corrected == Approx(T).epsilon(1e-9));
  // (6.7) as printed, with +sqrt(D), is right.
  const double x_printed = (R * lambda_T - L * rho_T - lambda_T * rho_0 + lambda_0 * rho_T -
                            lambda_T * rho_x * l0 + std::sqrt(D)) /
                           (2 * lambda_T * rho_x);
  CHECK(x_printed == Approx(x).epsilon(1e-9));
}

TEST_CASE("Without temperature coupling the inversion reduces to (7.4)") {
  InductanceLaw law{2.81e-3, 0.0288, 0.0, 0.433, kZeroCelsius, true};  // Table 7.2 in L* units
  const ResistanceLaw resistance{0.0, 0.0213, 10.18, kZeroCelsius};    // constantan-like
  for (double x : {0.010, 0.020, 0.030}) {
    const double measure = law(x, 300.0);
    CHECK(law.deflection(measure, 300.0) == Approx(x).epsilon(1e-12));  // (7.4)
    CHECK(invert_impedance(law, resistance, measure, resistance(x, 300.0)).deflection ==
          Approx(x).epsilon(1e-12));
  }
}

TEST_CASE("The inversion rejects measurements outside the model and an unobservable temperature") {
  const auto inductance = table_6_4_inductance();
  CHECK_THROWS_AS(invert_impedance(inductance, {0.0, 0.0, 10.0, kZeroCelsius}, 4.5e-6, 10.0),
                  OutsideModelRange);
  CHECK_THROWS_AS(invert_impedance(inductance, table_6_4_resistance(), 1e-6, 100.0),
                  OutsideModelRange);
}

TEST_CASE("The drive's power law (7.2) reproduces the thesis' power limits") {
  // U_b = 7 V, R_b = 10.75 ohm, R_m = 10.18 ohm: P(1) = 4.31 W, P(0.85) = 3.12 W, P(0.15) = 0.10 W
  // (section 7.3.2). (7.2) gives 4.3165 W at D = 1: the thesis truncates rather than rounds.
  const PwmSupply drive{7.0, 10.75 - 10.18};
  CHECK(drive.power(1.00, 10.18) == Approx(4.31).margin(0.01));
  CHECK(drive.power(0.85, 10.18) == Approx(3.12).margin(0.005));
  CHECK(drive.power(0.15, 10.18) == Approx(0.10).margin(0.005));
}

TEST_CASE("With a coupling term the inversion returns the deflection that produced the sum") {
  // Table 6.4's coil with lambda_T, and a neighbour's mutual inductance that grows with x
  // (nanohenries against the coil's microhenries, as in a bundle).
  const auto law = table_6_4_inductance();
  const auto coupling = [](double x) { return -5e-9 - 2e-7 * x; };
  const double temperature = 330.0;
  for (double x : {0.0, 0.01, 0.02, 0.04}) {
    const double measured = law(x, temperature) + coupling(x);
    CHECK(law.coupled_deflection(measured, temperature, coupling) == Approx(x).margin(1e-12));
    // Ignoring the coupling mistakes it for deflection.
    CHECK(std::abs(law.deflection(measured, temperature) - x) > 1e-4);
  }
  // A measure that the coupling would push to or below lambda_0 + lambda_T (T - T_ref) is none.
  const double floor = law.lambda_0 + law.lambda_T * (temperature - kZeroCelsius);
  CHECK(std::isnan(law.coupled_deflection(floor + 1e-9, temperature, [](double) { return 2e-9; })));
}
