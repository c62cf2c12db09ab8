#include "identification/model_order.h"

#include <algorithm>
#include <map>
#include <string>

namespace tcpmsim::fit {

std::vector<FamilyMembers> families_of(const std::vector<EffectCandidate>& tried) {
  std::vector<FamilyMembers> families;
  std::map<std::string, std::size_t> index;
  for (std::size_t k = 0; k < tried.size(); ++k) {
    const auto [found, added] = index.try_emplace(tried[k].name, families.size());
    if (added) families.emplace_back();
    FamilyMembers& family = families[found->second];
    (tried[k].order == 1 ? family.simplest : family.higher).push_back(k);
  }
  return families;
}

std::vector<std::size_t> longest_first(std::vector<std::size_t> candidates,
                                       const std::vector<EffectCandidate>& tried) {
  std::stable_sort(candidates.begin(), candidates.end(), [&](std::size_t a, std::size_t b) {
    return tried[a].parameters.size() > tried[b].parameters.size();
  });
  return candidates;
}

std::vector<std::size_t> higher_orders_to_try(const std::vector<FamilyMembers>& families,
                                              const std::vector<EffectCandidate>& tried,
                                              const std::vector<CandidateOutcome>& fitted,
                                              const std::vector<char>& finished,
                                              double bic_threshold) {
  const auto drop = [&](std::size_t k) {
    return finished[k] && fitted[k].status == "fitted" ? -fitted[k].delta_bic : 0.0;
  };
  double largest = 0.0;
  for (const auto& family : families)
    for (const std::size_t k : family.simplest) largest = std::max(largest, drop(k));
  std::vector<std::size_t> higher;
  for (const auto& family : families) {
    const bool evidence = std::any_of(family.simplest.begin(), family.simplest.end(), [&](auto k) {
      return drop(k) > bic_threshold && drop(k) >= kHigherOrderShare * largest;
    });
    if (evidence) higher.insert(higher.end(), family.higher.begin(), family.higher.end());
  }
  return longest_first(std::move(higher), tried);
}

}  // namespace tcpmsim::fit
