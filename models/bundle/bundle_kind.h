#pragma once

#include <string>
#include <vector>

#include "models/bundle/bundle_air.h"
#include "sim/registry.h"

namespace tcpmsim {

inline constexpr const char* kBundleCategory = "bundle";

// What a bundle tells the instances built after it: its member muscles ("b/m00", ...), in the
// order its records' columns follow.
struct BundleFacts {
  std::vector<std::string> members;
  // The fan's: with speed: controller (commanded) the port "<bundle>.fan_command" (0 to 1)
  // waits for a controller.
  BundleAir::Fan fan = BundleAir::Fan::none;
};

// Registers the category "bundle" (kind "parallel"): n muscles in parallel between common end
// plates, packed hexagonally or square, with their heat exchange, their wiring and a seeded
// spread of their parameters.
void register_bundle_kind(KindRegistry& kinds);

}  // namespace tcpmsim
