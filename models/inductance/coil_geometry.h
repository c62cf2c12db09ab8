#pragma once

namespace tcpmsim::inductance {

// A single-layer helical coil of round wire (thesis Figure 2.1), in SI units.
struct CoilGeometry {
  double radius = 0.0;         // [m] from the axis to the wire centre (r in (2.2))
  double length = 0.0;         // [m] along the axis (l); the pitch is length / turns
  double turns = 0.0;          // [1] N; may be non-integer (a spring's N = Lc / delta)
  double wire_diameter = 0.0;  // [m] delta

  double pitch() const { return length / turns; }
  double diameter() const { return 2.0 * radius; }
};

}  // namespace tcpmsim::inductance
