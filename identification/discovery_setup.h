#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "identification/fit_spec.h"
#include "identification/measured_roles.h"

namespace tcpmsim::fit {

struct DiscoverRequest {
  std::string model_file;               // the base model: a scenario replaying the measurement
  std::string data_file;                // the measurement (CSV or a tcpmsim record)
  std::vector<std::string> inputs;      // measured channels the model replays ("power")
  std::vector<std::string> outputs;     // compared channels: "force", or "force=load.force"
  std::vector<std::string> parameters;  // the base model's fitted parameters; empty: default
  std::vector<std::string> effects;     // candidates tried; empty: the whole catalogue
  int max_order = 0;  // the highest model order tried within a family (elements, branches); 0: all
  std::vector<std::string> overrides;  // --set on the model
  double validate_from = 0.0;          // [s]: identification before, validation from here
  int threads = 2;                     // candidates fitted at once
  int starts = 8;                      // multistart points per fit
  std::uint64_t seed = 1;              // of the multistart
  double bic_threshold = 10.0;         // a candidate must lower the BIC by more than this,
  double min_gap_shrink = 0.0;  // must not raise the validation RMSE (shrink by more than this),
  double min_signature = 3.0;   // and what it changes must explain the base model's validation
                                // residual: its matched-filter z (see CandidateOutcome)
  bool despike_all = false;     // remove spikes from every output, not the coil's measure only
  // The noise floor of outputs whose floor is known ("force=2 mN"); the others' is estimated
  // from the data (difference_noise_floor).
  std::vector<std::string> noise;
  // `none` needs every output's base validation RMSE within this fraction above its floor.
  double floor_margin = 0.25;
  // A significant candidate must also close this share of the gap above the floor to be named:
  // of the outputs the base model misses by more than the margin, or of all combined where it
  // misses none (closes_enough_of_gap).
  double min_gap_closed = 0.2;
  // Significant candidates within bic_threshold of the best whose validation changes correlate
  // by at least this are aliases: the first in the catalogue's order is named
  // (identification/candidate_aliases.h).
  double alias_correlation = 0.9;
};

// The measurement, the base model and the fit problem discover works on, checked.
struct DiscoverSetup {
  DiscoverRequest request;
  FitSpec base;                        // the base model's fit (parameters with bounds)
  std::vector<std::string> overrides;  // every scenario discover builds takes these first
  std::vector<std::size_t> cleaned;    // per output: spike samples replaced
  std::vector<double> floor;           // per output: the measurement's noise floor [unit]
  std::vector<bool> floor_given;       // per output: by --noise (else estimated from the data)
  MeasuredRoles roles;                 // the measured channels of the power and the deflection
  std::shared_ptr<const UnitSystem> units;
};

// Reads and checks everything before any fit: the model and data files, that every input is
// measured and replayed by the model, every output measured and published by the model, the
// base parameters and the validation split. Throws ConfigError (the model, --set) or
// UsageError (a command-line choice) with the reason.
DiscoverSetup setup_discovery(const DiscoverRequest& request,
                              std::shared_ptr<const UnitSystem> units);

// The noise each output is weighted by before the base fit: the RMS of its residual at the
// model's own values (1 where that is zero).
std::vector<double> initial_noise(const FitProblem& problem);

// The measurement with spikes replaced in `channels` (an empty name: none): a sample that
// stands more than 5 noise standard deviations (robustly, from the second differences) off both
// the median of the three samples before it and that of the three after, on the same side,
// takes their mean. Isolated and adjacent spikes go; a step's edge (it agrees with one side) and
// a ramp (it lies between) stay, and so does a sample next to a one-sample excursion of one of
// the `inputs` (by the same test, spanning at least 2 % of the input's range), which drives a
// true one. `replaced` counts them per channel of `channels`.
MeasuredData without_spikes(const MeasuredData& data, const std::vector<std::string>& channels,
                            const std::vector<std::string>& inputs,
                            std::vector<std::size_t>& replaced);

}  // namespace tcpmsim::fit
