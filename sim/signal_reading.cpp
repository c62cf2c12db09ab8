#include "sim/signal_reading.h"

namespace tcpmsim {

std::unique_ptr<Signal> read_signal(const ConfigNode& node, std::string_view si_unit,
                                    const SignalContext& context) {
  node.mark_part("signal in " + std::string(si_unit));
  const KindRegistry& kinds = *context.kinds;
  const Category& category = kinds.category(kSignalCategory);
  if (node.is_scalar()) {
    const Kind& constant = kinds.registered(kSignalCategory, category.scalar_kind);
    return kinds.builder<SignalBuilder>(constant)(node, si_unit, context);
  }
  if (!node.is_map()) node.fail("expected a quantity or a signal mapping with a 'type'");
  const Kind& kind = kinds.select(kSignalCategory, node);
  return kinds.builder<SignalBuilder>(kind)(node, si_unit, context);
}

}  // namespace tcpmsim
