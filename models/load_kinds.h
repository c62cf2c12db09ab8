#pragma once

#include "sim/registry.h"

namespace tcpmsim {

inline constexpr const char* kLoadCategory = "load";

// Registers the category "load" (what holds the muscles) and its kinds: deflection and force
// (a testing machine in position or force mode) and hanging_mass.
void register_load_kinds(KindRegistry& kinds);

}  // namespace tcpmsim
