#pragma once

#include "sim/io/hdf5_writer.h"

#include <string>

#include "identification/fit_spec.h"

namespace tcpmsim::fit {

// What `tcpmsim fit` prints: the estimates with standard errors, what the data do not identify,
// and the scores on the identification and validation windows.
std::string fit_summary(const FitSpec& spec, const FitResult& result);

// The same as JSON: {"parameters": [{"path", "unit", "initial", "estimate", "standard_error",
// "identifiable"}...], "correlation": [[...]], "rank", "identifiability": [...],
// "identification": {"<channel>": {"rmse", "nrmse", "r2"}}, "validation": {...}, "cost",
// "iterations", "simulations", "termination"}. Unidentified values are null.
std::string fit_json(const FitSpec& spec, const FitResult& result);

// The model scenario with the estimates written in (in the parameters' SI units) and its
// measurement set to the data: runnable as it is.
std::string fitted_scenario_yaml(const FitSpec& spec, const FitResult& result);

// Writes DIR/fit.json, DIR/fitted.yaml and DIR/fit.h5 (the measured channels and the model's
// outputs before and after the fit, over both windows) and returns their paths.
std::vector<std::string> write_fit_outputs(const std::string& directory, const FitSpec& spec,
                                           const FitResult& result,
                                           const Provenance& provenance = {});

}  // namespace tcpmsim::fit
