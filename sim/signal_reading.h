#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string_view>

#include "sim/config/config_node.h"
#include "sim/registry.h"
#include "sim/signal.h"

namespace tcpmsim {

// What a signal's reader needs besides its section.
struct SignalContext {
  std::uint64_t seed = 0;  // the scenario seed; each random signal draws its own stream
  double duration = 0.0;   // the time the signal is meant to cover [s]
  const KindRegistry* kinds = nullptr;  // where the signal kinds are registered
  // The scenario's measurement (measurement.file, found beside the scenario; fit and discover
  // set it to their --data): what a data signal without a file of its own replays. Empty: none.
  std::string measurement_file;
};

// Reads a signal of one kind from its section (values in `si_unit`). The kind registered as
// the category's default also reads a bare quantity (a constant).
using SignalBuilder = std::function<std::unique_ptr<Signal>(
    const ConfigNode& node, std::string_view si_unit, const SignalContext& context)>;

// The category every signal kind registers in.
inline constexpr const char* kSignalCategory = "signal";

// Reads a signal whose values are in `si_unit`: a bare quantity is a constant, a mapping
// names its kind with `type`.
std::unique_ptr<Signal> read_signal(const ConfigNode& node, std::string_view si_unit,
                                    const SignalContext& context);

}  // namespace tcpmsim
