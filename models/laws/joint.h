#pragma once

// The cable geometry of an antagonistic joint (thesis ch. 5 and section 7.5): two muscles pull
// through cables wound on a pulley of radius r, the left one lengthening as the angle grows, the
// right one shortening,
//     x_left = x0_left + r theta,     x_right = x0_right - r theta,
// with x0 the pre-deflections (pre-strain) at theta = 0. The plant (AntagonisticJoint) maps the
// angle to the cables; a self-sensing controller maps its two estimated deflections back, each
// with its own values of the geometry.
namespace tcpmsim {

struct JointGeometry {
  double radius = 0.0;                // r [m]
  double left_pre_deflection = 0.0;   // x0_left [m]
  double right_pre_deflection = 0.0;  // x0_right [m]
};

namespace joint {

inline double left_deflection(const JointGeometry& g, double angle) {
  return g.left_pre_deflection + g.radius * angle;
}
inline double right_deflection(const JointGeometry& g, double angle) {
  return g.right_pre_deflection - g.radius * angle;
}

// The inverse from both deflections, averaged:
//     theta = ((x_left - x0_left) - (x_right - x0_right)) / (2 r).
// Averaging cancels an error the two share (a common bias of the two estimates).
inline double angle_from_deflections(const JointGeometry& g, double left, double right) {
  return ((left - g.left_pre_deflection) - (right - g.right_pre_deflection)) / (2.0 * g.radius);
}

// The small-signal stiffness -d(torque)/d(theta) = r^2 (k_left + k_right) + k_s, with k each
// muscle's dF/dx (0 when slack) and k_s an external spring.
inline double stiffness(const JointGeometry& g, double left, double right, double spring) {
  return g.radius * g.radius * (left + right) + spring;
}

}  // namespace joint
}  // namespace tcpmsim
