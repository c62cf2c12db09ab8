#pragma once

#include <cstddef>
#include <vector>

#include "identification/discovery.h"
#include "identification/effect_catalogue.h"

// How discover chooses a family's model order (forward selection): every family's simplest
// members first, then the higher orders of the families they give evidence for.
namespace tcpmsim::fit {

// One family's candidates (indices into the catalogue's list): its simplest members (order 1)
// and its higher orders.
struct FamilyMembers {
  std::vector<std::size_t> simplest, higher;
};

// The families of `tried`, in the order they first appear.
std::vector<FamilyMembers> families_of(const std::vector<EffectCandidate>& tried);

// A family's higher orders are tried where one of its simplest members lowered the BIC by at
// least this share of the largest drop of any simplest member: a family an order of magnitude
// behind the best one is not where the effect is, and its higher orders (a switched fan, four
// play operators) are the catalogue's dearest fits.
inline constexpr double kHigherOrderShare = 0.1;

// `candidates` in the order to start them: the most parameters (the longest fits) first.
std::vector<std::size_t> longest_first(std::vector<std::size_t> candidates,
                                       const std::vector<EffectCandidate>& tried);

// The higher orders to try, longest first, given the outcomes of the candidates marked
// `finished` (the others are not read): those of the families where a simplest member lowered
// the BIC by more than `bic_threshold` and by kHigherOrderShare of the largest drop of any.
std::vector<std::size_t> higher_orders_to_try(const std::vector<FamilyMembers>& families,
                                              const std::vector<EffectCandidate>& tried,
                                              const std::vector<CandidateOutcome>& fitted,
                                              const std::vector<char>& finished,
                                              double bic_threshold);

}  // namespace tcpmsim::fit
