#include "identification/candidate_aliases.h"

#include <algorithm>
#include <cmath>

namespace tcpmsim::fit {

double weighted_dot(const std::vector<std::vector<double>>& a,
                    const std::vector<std::vector<double>>& b, const std::vector<double>& noise) {
  double sum = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    for (std::size_t i = 0; i < a[k].size(); ++i) sum += a[k][i] * b[k][i] / (noise[k] * noise[k]);
  }
  return sum;
}

double change_correlation(const std::vector<std::vector<double>>& a,
                          const std::vector<std::vector<double>>& b,
                          const std::vector<double>& noise) {
  const double norms = std::sqrt(weighted_dot(a, a, noise) * weighted_dot(b, b, noise));
  return norms > 0 ? weighted_dot(a, b, noise) / norms : 0.0;
}

namespace {

std::size_t catalogue_position(const std::string& name, const std::vector<std::string>& order) {
  return static_cast<std::size_t>(std::find(order.begin(), order.end(), name) - order.begin());
}

bool competes(const CandidateOutcome& candidate) {
  return candidate.status == "fitted" && candidate.significant && !candidate.superseded;
}

}  // namespace

void name_first_of_aliases(std::vector<CandidateOutcome>& ranked, const std::vector<double>& noise,
                           double bic_margin, double min_correlation,
                           const std::vector<std::string>& catalogue_order) {
  if (ranked.empty() || !competes(ranked.front())) return;
  const CandidateOutcome& best = ranked.front();
  std::vector<std::size_t> group{0};
  for (std::size_t i = 1; i < ranked.size(); ++i) {
    const CandidateOutcome& other = ranked[i];
    if (!competes(other) || other.name == best.name) continue;
    if (other.delta_bic - best.delta_bic >= bic_margin) continue;
    if (change_correlation(best.validation_change, other.validation_change, noise) <
        min_correlation)
      continue;
    group.push_back(i);
  }
  if (group.size() < 2) return;
  const std::size_t named = *std::min_element(group.begin(), group.end(), [&](auto a, auto b) {
    return catalogue_position(ranked[a].name, catalogue_order) <
           catalogue_position(ranked[b].name, catalogue_order);
  });
  CandidateOutcome& chosen = ranked[named];
  chosen.aliases.clear();
  for (std::size_t i : group) {
    if (i == named) continue;
    chosen.aliases.push_back(
        {ranked[i].name,
         change_correlation(chosen.validation_change, ranked[i].validation_change, noise),
         ranked[i].delta_bic - chosen.delta_bic});
  }
  std::rotate(ranked.begin(), ranked.begin() + static_cast<long>(named),
              ranked.begin() + static_cast<long>(named) + 1);
}

}  // namespace tcpmsim::fit
