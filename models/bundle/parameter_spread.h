#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "sim/config/config_node.h"
#include "sim/context.h"
#include "sim/system.h"

namespace tcpmsim {

// Muscle-to-muscle variation in a bundle: no two muscles of a real bundle are alike. The
// bundle's `spread` section maps a muscle parameter (its path under the muscle section,
// "mechanics.k1") to a distribution of the factor each member's value is multiplied by:
//   {distribution: normal, relative: s}   1 + s z, z standard normal truncated at |z| <= 3
//                                         (s <= 0.3, so every factor stays above 0.1);
//   {distribution: uniform, relative: w}  1 + w (2u - 1), u uniform in [0, 1) (w < 1).
// Each key draws its members' factors in member order from its own stream of the scenario's
// seed (purpose "<bundle>.spread.<key>"), so the same seed gives the same bundle, and adding a
// key leaves the others' draws alone. A member's value follows the muscle section times its
// factor in every run: it is a derived parameter, set through the muscle section.
class ParameterSpread {
 public:
  // `first_member` is built already: the keys are checked against its parameters.
  static ParameterSpread from_config(const std::optional<ConfigNode>& section,
                                     const std::string& bundle, std::size_t members,
                                     const std::string& first_member, std::uint64_t seed,
                                     const SystemBuilder& system);

  bool has(const std::string& key) const { return factors_.count(key) > 0; }
  // Member k's factor for `key`; 1 for a key without spread.
  double factor(const std::string& key, std::size_t member) const;
  // Every key's factors, member by member.
  const std::map<std::string, std::vector<double>>& factors() const { return factors_; }
  // Makes `member`'s spread parameters follow the muscle section times its factors, except
  // the keys in `handled` (which the caller scales with more than the spread).
  void apply(std::size_t k, const std::string& member, SystemBuilder& system,
             const std::set<std::string>& handled) const;

 private:
  std::map<std::string, std::vector<double>> factors_;
};

// Makes the parameter `path` follow its value as built times `factor` of the run's context.
void derive_scaled(SystemBuilder& system, const std::string& path,
                   std::function<double(const Context&)> factor, std::string explanation);

}  // namespace tcpmsim
