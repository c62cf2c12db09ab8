#pragma once

#include "sim/registry.h"

namespace tcpmsim {

inline constexpr const char* kJointKind = "joint";

// Registers the load kind "joint": an antagonistic pair of muscles on a pulley
// (models/antagonistic_joint.h) and its angle encoder.
void register_joint_load(KindRegistry& kinds);

}  // namespace tcpmsim
