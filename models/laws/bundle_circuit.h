#pragma once

namespace tcpmsim {

// How a bundle's muscles are wired to one supply.
enum class BundleWiring { series, parallel };
// What the supply holds: its terminal voltage (behind a series resistance), the current, or
// the power delivered into the bundle.
enum class SupplyMode { voltage, current, power };

// The bundle's terminal voltage and the current through its terminals.
struct OperatingPoint {
  double voltage = 0.0;  // [V]
  double current = 0.0;  // [A]
};

namespace bundle_circuit {

// The bundle as one resistor: R_1 + ... + R_n in series, 1 / (1/R_1 + ... + 1/R_n) in parallel.
// `sum` is the sum of the members' resistance_term.
inline double resistance_term(BundleWiring wiring, double member) {
  return wiring == BundleWiring::series ? member : 1.0 / member;
}
inline double resistance(BundleWiring wiring, double sum) {
  return wiring == BundleWiring::series ? sum : 1.0 / sum;
}

// The operating point of a bundle of resistance `load` on a source of value `source` (V, A or
// W) behind `series_resistance`:
//   voltage: I = U / (R_s + R) (PwmSupply's on-current),  current: I = I_s,  power: I = sqrt(P /
//   R);  then V = I R.
OperatingPoint operating_point(SupplyMode mode, double source, double series_resistance,
                               double load);

// What the source gives: the bundle's V I and the series resistance's R_s I^2 [W].
inline double source_power(const OperatingPoint& point, double series_resistance) {
  return point.voltage * point.current + series_resistance * point.current * point.current;
}

// The current through member k of resistance `member`: the bundle's current in series, V / R_k
// in parallel, so that parallel members share the current in the inverse ratio of their
// resistances.
inline double member_current(BundleWiring wiring, const OperatingPoint& point, double member) {
  return wiring == BundleWiring::series ? point.current : point.voltage / member;
}

}  // namespace bundle_circuit

}  // namespace tcpmsim
