#pragma once

#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "identification/discovery_runs.h"

// discover --max-effects: the effects the runs named, refitted together. Each run fitted its
// own effect beside the base laws with the effects named before it held at their values, so an
// early effect's values took up some of what a later one explains (a Dahl element's stiffness
// named first on data that also relax slowly). Refitted together from the values the runs left,
// the model carrying them all can only lower its identification error; the validation window,
// which no fit has seen, says whether it is the better model.
namespace tcpmsim::fit {

struct JointRefit {
  std::string directory;              // where its files go: out/joint
  std::string start_model;            // the model the runs ended with, which it starts from
  std::size_t effect_parameters = 0;  // freed besides the base laws'
  FitSpec spec;                       // the base laws' and every named effect's parameters
  FitResult result;
  std::vector<double> floor;  // per output, the measurement's noise floor
  // Per output, the start model's RMSEs on the two windows.
  std::vector<double> start_identification_rmse;
  std::vector<double> start_validation_rmse;
  // Its validation error, combined over the floors, is no larger than the start model's, and it
  // fits every output to its floor where the start model does: it is the model that carries
  // every named effect.
  bool better = false;
  bool at_floor = false;     // every output's validation RMSE within the margin of its floor
  std::string still_missed;  // the outputs it misses, in floors ("force 1.8 times"), else ""
  std::string failure;       // why the refit could not be made ("" when it was)
};

// Whether the runs call for a joint refit: two or more named an effect.
bool joint_refit_due(const std::vector<EffectRun>& runs);

// The runs' final model (the one effect_runs_summary names) fitted with the base laws'
// parameters (`first`'s --parameters, or discover's defaults for that model) and every named
// effect's (EffectRun::effect_parameters, within the bounds its run fitted them in), starting
// from the model's values, on `first`'s measurement, outputs and windows; each output weighted
// by the start model's identification RMSE. A fit that cannot be made (the model does not load,
// its fit fails) is returned with `failure` set: the runs stand without it. A value on a bound
// starts there (clamped: the runs' files can hold it a rounding step beyond).
JointRefit refit_jointly(const DiscoverRequest& first, const std::vector<EffectRun>& runs,
                         const std::string& out, std::shared_ptr<const UnitSystem> units);

// What `tcpmsim discover` prints of it: the parameters freed, the identification and validation
// errors before and after per output, and which model carries the effects.
std::string joint_refit_summary(const JointRefit& joint);

// Its part of effects.json: {"directory", "model" (its fitted.yaml; null when it failed),
// "start_model", "parameters", "effect_parameters", "identification_rmse" and "validation_rmse"
// ({channel: [start, refitted]} in the outputs' SI units), "better", "at_noise_floor",
// "converged", "failure"}.
nlohmann::json joint_refit_json(const JointRefit& joint);

}  // namespace tcpmsim::fit
