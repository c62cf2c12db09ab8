#pragma once

#include <string>
#include <vector>

#include "identification/fit_problem.h"
#include "identification/measured_roles.h"
#include "sim/context.h"
#include "sim/io/measured_data.h"
#include "sim/scenario.h"

namespace tcpmsim::fit {

// A candidate of `tcpmsim discover`: one member of a family of effects the base model lacks
// (hysteresis as one Dahl element or as a Prandtl-Ishlinskii operator of several radii), as the
// scenario overrides that attach it to the muscle and the parameters a refit frees besides the
// base model's, with bounds. Every member nests the base model: at its `nested` values (zero
// size: no weight, no stiffness, no share) the augmented model is the base model, so a refit
// that starts there can only end at or below the base fit's cost.
struct EffectCandidate {
  std::string name;                      // the family, which a verdict names: "hysteresis"
  std::string member;                    // the form within it: "Dahl element, free radius"
  int order = 1;                         // elements or branches of that form
  std::string description;               // what it models
  std::string signature;                 // the diagnostic that should give it away
  std::vector<std::string> overrides;    // attach it ("muscle.effects=[...]"), or none
  std::vector<FitParameter> parameters;  // freed by the refit, in the augmented model
  std::vector<double> nested;            // per parameter: where the member is the base model
};

// The families of the catalogue, in its order, as the kinds of the standard registry declare
// them (Kind::candidates, models/effects/effect_candidates.h).
std::vector<std::string> effect_names();

// How discover tries `kind` (its declared families and their members, or why not), for
// `tcpmsim kinds` (sim/kind_listing.h's KindNotes); "" for a kind that declares nothing.
std::string describe_candidates(const Kind& kind, bool markdown);

// The one muscle of a base model (its instance name); std::invalid_argument if it has none or
// several.
std::string only_muscle(const System& system);

// A candidate that cannot join this base model, and why ("thermal_lag: the muscle reports no
// temperature").
struct SkippedCandidate {
  std::string name;
  std::string reason;
};

struct Candidates {
  std::vector<EffectCandidate> candidates;  // every member of every family that attaches
  std::vector<SkippedCandidate> skipped;
};

// What the catalogue reads beyond the base model's parameters: which measured channels carry
// the power and the deflection, and how warm the fitted base model runs over the data.
struct CatalogueContext {
  MeasuredRoles roles;
  double temperature_peak = 0.0;  // the base model's warmest [K]; 0: not known
};

// The catalogue for `base` (one muscle, reduced or physical thermal form), its scales taken
// from the base model's parameters in `fitted`, the deflection's range and the power's peak from
// the channels of `data` that `context.roles` names; `outputs` are the model outputs compared
// (an inductance candidate needs one of the coil's). Effects the muscle already has are kept: a
// candidate is appended to its `effects`.
Candidates effect_candidates(const Scenario& base, const Context& fitted, const MeasuredData& data,
                             const std::vector<std::string>& outputs,
                             const CatalogueContext& context = {});

}  // namespace tcpmsim::fit
