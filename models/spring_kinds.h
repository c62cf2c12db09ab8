#pragma once

#include "sim/registry.h"

namespace tcpmsim {

// Registers the category "spring" and its kind coil_spring: a metal coil spring as lumped
// windings between two imposed ends (thesis ch. 4), optionally sensing its own inductance.
void register_spring_kinds(KindRegistry& kinds);

}  // namespace tcpmsim
