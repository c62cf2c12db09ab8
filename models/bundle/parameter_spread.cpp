#include "models/bundle/parameter_spread.h"

#include <cmath>

#include "sim/random_stream.h"

namespace tcpmsim {

namespace {

constexpr double kTruncation = 3.0;  // normal deviates beyond 3 sigma are drawn again

std::vector<double> draw_factors(const ConfigNode& node, const std::string& purpose,
                                 std::size_t members, std::uint64_t seed) {
  node.declare({"distribution", "relative"});
  const bool normal = node.choice("distribution", {"normal", "uniform"}) == "normal";
  const double relative = normal ? node.number("relative", ValueCheck::between(0.0, 0.3))
                                 : node.number("relative", ValueCheck::between(0.0, 0.99));
  RandomStream stream(seed, purpose);
  std::vector<double> factors;
  for (std::size_t k = 0; k < members; ++k) {
    if (normal) {
      double z = stream.normal();
      while (std::abs(z) > kTruncation) z = stream.normal();
      factors.push_back(1.0 + relative * z);
    } else {
      factors.push_back(1.0 + relative * (2.0 * stream.uniform() - 1.0));
    }
  }
  return factors;
}

}  // namespace

ParameterSpread ParameterSpread::from_config(const std::optional<ConfigNode>& section,
                                             const std::string& bundle, std::size_t members,
                                             const std::string& first_member, std::uint64_t seed,
                                             const SystemBuilder& system) {
  ParameterSpread spread;
  if (!section) return spread;
  if (!section->is_map())
    section->fail("expected a mapping of muscle parameters (mechanics.k1) to distributions");
  for (const auto& [key, node] : section->entries()) {
    if (!system.declares_parameter(first_member + "." + key)) {
      node.fail("the bundle's muscles have no numeric parameter '" + key +
                "' (expected a key path under the muscle section, such as mechanics.k1)");
    }
    spread.factors_[key] = draw_factors(node, bundle + ".spread." + key, members, seed);
  }
  return spread;
}

double ParameterSpread::factor(const std::string& key, std::size_t member) const {
  const auto found = factors_.find(key);
  return found == factors_.end() ? 1.0 : found->second[member];
}

void ParameterSpread::apply(std::size_t k, const std::string& member, SystemBuilder& system,
                            const std::set<std::string>& handled) const {
  for (const auto& [key, factors] : factors_) {
    if (handled.count(key)) continue;
    const double factor = factors[k];
    derive_scaled(
        system, member + "." + key, [factor](const Context&) { return factor; },
        "the muscle section's value times the member's spread factor " + std::to_string(factor));
  }
}

void derive_scaled(SystemBuilder& system, const std::string& path,
                   std::function<double(const Context&)> factor, std::string explanation) {
  system.derive(
      path,
      [path, factor = std::move(factor)](const Context& context) {
        const auto& model = context.system();
        const auto index = static_cast<std::size_t>(*model.parameter_index(path));
        return model.parameters()[index].declaration.value * factor(context);
      },
      std::move(explanation));
}

}  // namespace tcpmsim
