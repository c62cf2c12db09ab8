#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "identification/discovery_diagnostics.h"
#include "identification/discovery_setup.h"
#include "identification/effect_catalogue.h"

// `tcpmsim discover` (issue 12): fit a base model to the identification window of a
// measurement, locate where it disagrees with the validation window, refit the base model with
// each named effect of the catalogue attached, rank them by BIC and validation error, and name
// the effect that is missing, or none.
namespace tcpmsim::fit {

// One candidate's outcome.
struct CandidateOutcome {
  std::string name;    // its family, which a verdict names
  std::string member;  // its form within the family
  int order = 1;
  std::string description;
  std::string status;  // "fitted", "failed" (message in reason), "skipped" (reason)
  std::string reason;
  // The refit's cost at its nested start (the base model, the effect at zero size) and whether
  // it was fitted again from there because the multistart ended above it.
  double nested_cost = 0.0;
  bool retried = false;
  // Whether it was fitted again from its best drawn start because the refit from the nested
  // start never left it (see refit_nested), and whether that refit is the one kept.
  bool retried_from_drawn = false;
  bool drawn_kept = false;
  // Another member of its family has the lower BIC: only the best member of a family competes.
  bool superseded = false;
  FitSpec spec;  // the augmented model's fit
  FitResult result;
  double bic = 0.0;
  double delta_bic = 0.0;               // against the base model; negative is better
  std::vector<double> validation_rmse;  // per output
  double gap_shrink = 0.0;              // 1 - combined rmse_aug / rmse_base
  double gap_closed = 0.0;              // of the gap above the noise floor (NaN: none)
  // Of the gap above the floor of the outputs the base model misses (see missed_gap_closed):
  // what a significant candidate must close enough of. NaN when the base misses none.
  double missed_gap_closed = 0.0;
  // Its signature in the validation window, which the fit has not seen: the change d it makes
  // to the outputs against the base model's residual r (noise-weighted sums over the outputs),
  // as the correlation sum(r d) / (|r| |d|), and as the matched-filter statistic
  // z = sum(r d / sigma^2) / sqrt(sum(d^2 / sigma^2)), standard normal when r is only noise.
  double signature_match = 0.0;
  double signature_z = 0.0;
  // Per output: the lag-1 autocorrelation of what the candidate leaves of the validation data,
  // and the evidence share it gives a sample (evidence_share): the BIC change and the signature
  // z count the samples of noise that is not white for what they are worth.
  std::vector<double> residual_autocorrelation;
  std::vector<double> evidence_shares;
  std::string signature;           // the diagnostic that should give it away
  std::string signature_evidence;  // that diagnostic's value on the base residual
  bool significant = false;
  // The change d above, per output (not written to discovery.json).
  std::vector<std::vector<double>> validation_change;
  // Significant candidates the data do not tell from this one (identification/candidate_aliases.h).
  struct Alias {
    std::string name;
    double correlation = 0.0;  // of the two changes, noise-weighted
    double delta_bic = 0.0;    // its BIC against this one's
  };
  std::vector<Alias> aliases;
  double seconds = 0.0;  // wall time of its fit
};

// What a discovery concludes: an effect is named (the best significant candidate); `none`, the
// base model already fits to the noise (every output's validation RMSE within the margin of
// its noise floor, and no candidate significant; a residual that is not white does not stop it,
// see at_noise_floor); or `unexplained`, the base model misses by more than the noise and no
// candidate explains it.
enum class VerdictKind { effect, none, unexplained };
const char* verdict_kind_name(VerdictKind kind);

struct Discovery {
  DiscoverSetup setup;
  FitResult base;
  double base_bic = 0.0;
  std::vector<double> noise;        // per output, the base fit's identification RMSE: the weights
  ResidualDiagnostics diagnostics;  // of the base model on the validation window
  std::vector<CandidateOutcome> candidates;  // ranked: significant first, then by delta_bic
  std::vector<SkippedCandidate> skipped;
  VerdictKind kind = VerdictKind::none;
  std::string verdict;  // an effect's name, "none" or "unexplained"
  // Whether each output's base validation RMSE is at the noise floor (within the margin; see
  // at_noise_floor), and the share of the above-noise gap, (rmse_base - rmse_aug) /
  // (rmse_base - floor) with outputs combined over their floors, that the verdict's effect
  // closes (0 without one; NaN when the base is already at the floor).
  std::vector<bool> at_noise;
  double gap_closed = 0.0;
  int base_rounds = 1;  // candidate rounds: a second when re-tuning improved the base model
  int simulations = 0;
  double seconds = 0.0;
};

Discovery discover(const DiscoverSetup& setup);

// The share of the above-noise gap an augmented model closes: (r_base - r_aug) / (r_base - 1),
// r the combined RMSEs over the floors; NaN when the base is at or below the floor.
double above_noise_gap_closed(const std::vector<double>& base_rmse,
                              const std::vector<double>& augmented_rmse,
                              const std::vector<double>& floor);

// The share of the above-noise gap an augmented model closes on the outputs the base model
// misses, those whose validation RMSE is above (1 + margin) times their floor: the outputs
// `none` would not pass. NaN when it misses none. An output at its floor does not dilute the
// share: a force that misses by 1.4 floors beside an L* at 1.1 is a gap of the force alone.
double missed_gap_closed(const std::vector<double>& base_rmse,
                         const std::vector<double>& augmented_rmse,
                         const std::vector<double>& floor, double margin);

// The rule a significant candidate must also pass: it closes at least `min_share` of the gap
// above the noise floor. Where the base model misses an output, of that output's gap (see
// missed_gap_closed); where it misses none but lies above the floors combined, of that combined
// gap (above_noise_gap_closed): at the floor too, an effect that takes a sliver off what the
// base model leaves is not what is missing (a model is never exactly the data's law, and at low
// noise a candidate that absorbs a few percent of that rest is significant by BIC and z alone);
// at or below the floors, nothing is asked.
bool closes_enough_of_gap(const std::vector<double>& base_rmse,
                          const std::vector<double>& augmented_rmse,
                          const std::vector<double>& floor, double margin, double min_share);

// Whether each output's base validation RMSE is at its noise floor: rmse <= (1 + margin) floor.
// Whiteness is not required. A model is never exactly the data's law, and with thousands of
// samples Ljung-Box finds a structured part of a few percent of the noise variance; the margin is
// the size the user asks discover to explain, and the report names a smaller, non-white rest.
std::vector<bool> at_noise_floor(const std::vector<double>& rmse, const std::vector<double>& floor,
                                 double margin);

// The RMS of a residual's part above white noise of the floor: sqrt(max(0, rmse^2 - floor^2)).
double structured_rms(double rmse, double floor);

// The combined validation RMSE of several outputs, each over its noise: sqrt(mean (rmse/noise)^2).
double combined_rmse(const std::vector<double>& rmse, const std::vector<double>& noise);

// BIC of a least-squares fit with an unknown variance per output:
// sum_k n ln(RSS_k / n) + p ln(N), with RSS_k = n rmse_k^2 and N = n * outputs.
double bic(const WindowScore& identification, std::size_t parameters);

// The evidence one sample of an output's residual carries when the noise is not white, as the
// share (1 - rho) / (1 + rho) of a white sample's, rho the residual's lag-1 autocorrelation
// (clamped to [0, 0.99]): n samples of AR(1) noise tell a smooth change apart as well as
// n (1 - rho) / (1 + rho) independent ones. 1 for white noise.
double evidence_share(std::span<const double> residual);

// A candidate's BIC against the base model's where each output's samples carry `shares` of a
// white sample's evidence: sum_k share_k n ln(RSS_k / RSS_base,k) + (p - p_base) ln(N). With
// every share 1 it is bic(candidate) - bic(base).
double bic_change(const WindowScore& candidate, std::size_t parameters, const WindowScore& base,
                  std::size_t base_parameters, const std::vector<double>& shares);

}  // namespace tcpmsim::fit
