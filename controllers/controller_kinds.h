#pragma once

#include "sim/registry.h"

namespace tcpmsim {

// Registers the categories drive (joule, muscle_drive), estimator (self_sensing) and
// controller (pid).
void register_controller_kinds(KindRegistry& kinds);

}  // namespace tcpmsim
