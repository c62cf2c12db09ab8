#pragma once

#include <string>
#include <vector>

#include "identification/discovery.h"

// Candidates the data do not tell apart (issue 28). Two effects can change a measurement in
// nearly the same way: on a heating protocol whose temperature follows the power through one
// lag, a heat loss that grows with the temperature rise (radiation, free convection) and a
// convection boosted by a lagged copy of the power both add a loss ~ dT^2. Their refits then
// differ in BIC by a few units, which under a misspecified model is no evidence. The verdict
// names such a group's first family in the catalogue's order (the commonest effect first) and
// lists the others as its aliases.
namespace tcpmsim::fit {

// sum_k sum_i a_k[i] b_k[i] / noise_k^2, over outputs k.
double weighted_dot(const std::vector<std::vector<double>>& a,
                    const std::vector<std::vector<double>>& b, const std::vector<double>& noise);

// The noise-weighted correlation of two changes of the outputs; 0 if either is zero.
double change_correlation(const std::vector<std::vector<double>>& a,
                          const std::vector<std::vector<double>>& b,
                          const std::vector<double>& noise);

// With `ranked` as discover ranks candidates (significant first, by delta BIC): the significant
// candidates whose BIC is within `bic_margin` of the best's and whose validation change
// correlates with the best's by at least `min_correlation` are aliases of one another. The one
// whose family comes first in `catalogue_order` moves to the front and records the others (the
// former best among them) in its `aliases`. Nothing changes when the best is not significant.
void name_first_of_aliases(std::vector<CandidateOutcome>& ranked, const std::vector<double>& noise,
                           double bic_margin, double min_correlation,
                           const std::vector<std::string>& catalogue_order);

}  // namespace tcpmsim::fit
