#pragma once

#include <functional>
#include <string>
#include <vector>

#include "identification/discovery.h"

// discover --max-effects N: real data often hold more than one missing effect, and discover
// names one a run (the one that explains most of the miss). While the model with the named
// effect still misses the noise floor, the next run starts from the model the run wrote
// (augmented.yaml), with its effect attached at its fitted values, and looks for another; each
// run writes its own directory. This is the procedure the guide gives by hand, run for the user.
namespace tcpmsim::fit {

struct EffectRun {
  int number = 1;         // 1 for the first run
  std::string directory;  // where it wrote its files
  std::string model;      // its base model (the run before's augmented.yaml after the first)
  std::string verdict;    // an effect's name, "none", "unexplained", or "failed"
  bool named = false;     // an effect was named
  // The share of the gap above the noise floor its effect closed, of what the run before left
  // (Discovery::gap_closed; NaN when the base is at the floor, 0 without an effect).
  double gap_closed = 0.0;
  // The outputs the model with its effect still misses, in floors ("force 3.66 times"); "" when
  // it fits every output to within the margin, or no effect was named.
  std::string still_missed;
  std::string failure;         // why a later run's base fit failed ("" otherwise)
  double floor_margin = 0.25;  // --floor-margin: "at the floor" is within this fraction above it
  // The named effect's parameters, as its refit freed them (paths in the augmented model, bounds
  // from the catalogue): what a joint refit of every named effect frees again (joint_refit.h).
  std::vector<FitParameter> effect_parameters;
};

// The model at the end of the runs, with every named effect: the last run's augmented model when
// it named one; after a later run that named none, that run's base model as it refitted it (the
// effects the runs before named, every base parameter refitted with them); after a failed run,
// the augmented model of the run before. With a joint refit that validates no worse, its model
// (joint_refit.h). Empty when no run named an effect.
struct FinalModel {
  std::string path;
  std::vector<std::string> effects;
  bool at_floor = false;     // fits every output to within the margin of its floor
  std::string still_missed;  // for a named effect's model that does not
};

struct JointRefit;
FinalModel final_model(const std::vector<EffectRun>& runs, const JointRefit* joint = nullptr);

// Where run `number` writes: `out` for the first, out/effect<number> for the later ones.
std::string effect_run_directory(const std::string& out, int number);

// What an earlier discover with --max-effects left in `out`: its effects.json (the marker: without
// it nothing is taken for a run), the effect<k> directories, from effect2 on while each holds
// a discovery.json or nothing (a run whose base fit failed), and its joint refit's directory
// (joint, holding a fit.json or nothing).
std::vector<std::string> earlier_effect_runs(const std::string& out);

// Throws UsageError when --model or --data lies where this discover writes: in an earlier run's
// directory it removes, in effect2 .. effect<max_effects>, or as one of the first run's files
// in `out`, or in `out`/joint. The first run loads them before, but a later run and effects.json
// would name a file that no longer holds what was read.
void check_outside_effect_runs(const DiscoverRequest& request, const std::string& out,
                               int max_effects);

// Removes earlier_effect_runs(out): a new discover into the same directory must not leave an
// older sequence's later runs beside its own as if it had made them. Returns what it removed.
std::vector<std::string> remove_earlier_effect_runs(const std::string& out);

// Whether another run is due after `discovery`: it named an effect, and the model with it still
// misses some output's noise floor by more than the margin (--floor-margin).
bool another_effect_due(const Discovery& discovery);

// The next run's request: the same measurement, channels, windows, candidates and settings, with
// the model the run before wrote as the base. Its --set overrides are in that model already (it
// is the resolved scenario), so the next run takes none.
DiscoverRequest next_effect_request(DiscoverRequest request, const std::string& augmented_model);

// Called once per run that ended, with its discovery and directory: writes the run's files
// (write_discovery) and whatever else the caller shows of it. A run's augmented.yaml must exist
// when it returns, for the next run to start from.
using EffectRunWriter = std::function<void(const Discovery&, const std::string& directory)>;

// Called before each later run starts (minutes of fitting), with its number, directory and
// base model.
using EffectRunAnnouncer =
    std::function<void(int number, const std::string& directory, const std::string& model)>;

// Runs discover up to `max_effects` times, the first on `first` into `out` (after
// check_outside_effect_runs and remove_earlier_effect_runs), stopping after a run that names no
// effect or whose model with the effect fits to the noise floor. The first run's failure
// propagates (FitFailure and the rest); a later run that fails (its base fit, its model, its
// files) ends the sequence with that run's verdict "failed" and the reason, the earlier runs'
// files standing.
std::vector<EffectRun> discover_effects(const DiscoverSetup& first, int max_effects,
                                        const std::string& out, const EffectRunWriter& write,
                                        const EffectRunAnnouncer& announce = {});

// What `tcpmsim discover --max-effects` prints after the runs: a line per run, the joint refit
// when there is one, the model that carries every named effect and whether it fits to the noise
// floor, and why the runs stopped.
std::string effect_runs_summary(const std::vector<EffectRun>& runs, int max_effects,
                                const JointRefit* joint = nullptr);

// effects.json: {"max_effects", "runs": [{"run", "directory", "model", "verdict", "gap_closed",
// "still_missed", "failure"}...], "effects": [names], "model": the file carrying every named
// effect (final_model; null without one), "at_noise_floor": whether that model fits every output
// to within the margin (null without one), "joint": the joint refit (joint_refit_json; null
// without one)}.
std::string effect_runs_json(const std::vector<EffectRun>& runs, int max_effects,
                             const JointRefit* joint = nullptr);

}  // namespace tcpmsim::fit
