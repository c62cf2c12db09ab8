#pragma once

#include "sim/registry.h"

namespace tcpmsim {

// Registers the controller kind "joint_angle": the angle of an antagonistic joint (a load of
// type joint) with a co-contraction level, through the joint's encoder or self-sensing.
void register_joint_angle_controller(KindRegistry& kinds);

}  // namespace tcpmsim
