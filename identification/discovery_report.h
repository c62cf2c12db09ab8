#pragma once

#include "sim/io/hdf5_writer.h"

#include <string>
#include <vector>

#include "identification/discovery.h"

namespace tcpmsim::fit {

// discovery.json: {"verdict": name|"none", "ranking": [{"effect", "delta_bic",
// "validation_rmse", "gap_shrink", "signature_match", "significant", "status"}...],
// "baseline": {"validation_rmse": {channel: ...}, "bic", "parameters"}, "augmented":
// {"effect", "validation_rmse", "parameters"}, "gap_shrink": 1 - rmse_aug / rmse_base,
// "diagnostics": {...}, "skipped": [...], "settings": {...}}.
std::string discovery_json(const Discovery& discovery);

// The outputs the model with the named effect still misses by more than the noise (its
// validation RMSE beyond the margin --floor-margin gives the floor, the test the base model
// takes), with their RMSEs in multiples of their floors: "force 3.1 times, inductance_measure
// 1.4 times". Another effect may be missing there. "" without a named effect or a miss.
std::string missed_with_effect(const Discovery& discovery);

// The outputs whose validation RMSE lies beyond (1 + margin) times their floor, in floors:
// "force 3.1 times, inductance_measure 1.4 times"; "" when none does.
std::string outputs_above_floor(const std::vector<FitOutput>& outputs,
                                const std::vector<double>& rmse, const std::vector<double>& floor,
                                double margin);

// A short human-readable report of the evidence (Markdown).
std::string discovery_report(const Discovery& discovery);

// What `tcpmsim discover` prints.
std::string discovery_summary(const Discovery& discovery);

// Writes into `directory`: discovery.json, report.md, baseline.yaml (the base model as refitted),
// augmented.yaml (with the verdict's effect, when there is one) and traces.h5 (/time,
// /measured, /baseline, /augmented and their residuals per channel, the windows, and the
// diagnostics of the base model's validation residual). Returns the paths written.
std::vector<std::string> write_discovery(const std::string& directory, const Discovery& discovery,
                                         const Provenance& provenance = {});

}  // namespace tcpmsim::fit
