#pragma once

#include "sim/registry.h"

namespace tcpmsim {

// Registers the effects a muscle's `effects` list may attach: maxwell_branch (a further
// viscoelastic branch in its force balance), thermal_softening (a parallel spring whose
// stiffness falls with temperature) and free_convection (a heat-loss law in its heat balance).
void register_effect_kinds(KindRegistry& kinds);

}  // namespace tcpmsim
