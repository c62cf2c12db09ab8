#include "models/model_kinds.h"

#include "models/bundle/bundle_kind.h"
#include "models/effects/effect_kinds.h"
#include "models/load_kinds.h"
#include "models/muscle.h"
#include "models/spring_kinds.h"

namespace tcpmsim {

void register_model_kinds(KindRegistry& kinds) {
  register_spring_kinds(kinds);
  register_muscle_kinds(kinds);
  register_effect_kinds(kinds);
  register_bundle_kind(kinds);
  register_load_kinds(kinds);
}

}  // namespace tcpmsim
