#pragma once

#include "sim/registry.h"

namespace tcpmsim {

// Every kind models/ provides: springs, muscles with their thermal forms and effects, loads.
void register_model_kinds(KindRegistry& kinds);

}  // namespace tcpmsim
