#pragma once

#include <string>
#include <utility>
#include <vector>

#include "identification/fit_problem.h"
#include "identification/measured_roles.h"
#include "identification/residual_diagnostics.h"

// Where a fitted base model disagrees with the validation window, read from its residuals
// r = measured - simulated with the diagnostics of residual_diagnostics.h, against the inputs
// and the model's own states: what `tcpmsim discover` reports and matches each candidate's
// signature against.
namespace tcpmsim::fit {

// A series the residual is held against: an input, a state of the base model, or a product.
struct Feature {
  std::string name;  // "power", "temperature rise", "deflection", "deflection rate",
                     // "last direction of motion", "temperature rise x deflection",
                     // "deflection^2"
  std::vector<double> values;
};

struct OutputDiagnostics {
  std::string channel;
  std::vector<double> residual;  // measured - simulated, at the validation samples
  LjungBox whiteness;
  Drift drift;
  std::vector<double> band_share;  // of the residual's variance, per band
  std::vector<std::pair<std::string, CrossCorrelation>> inputs;  // per replayed input
  std::vector<std::pair<std::string, double>> features;          // correlation with each
  LoopSpectrum loop;  // against the deflection, where one is measured
};

struct ResidualDiagnostics {
  std::vector<double> time;                      // the validation samples [s]
  std::vector<std::pair<double, double>> bands;  // [Hz]
  double bound = 0.0;                            // 1.96 / sqrt(n): white noise's 95 % band
  std::vector<Feature> features;
  std::vector<OutputDiagnostics> outputs;
  MeasuredRoles roles;  // the channels held as the power and the deflection
  // The correlation of the residual of `output` with the named feature, or NaN.
  double feature(std::size_t output, const std::string& name) const;
};

// The model's temperature at `values`, at the samples of `window`; empty where its muscle
// publishes none.
std::vector<double> model_temperature(const FitProblem& problem, const std::vector<double>& values,
                                      const TimeWindow& window);

// The diagnostics of the model at `values` on `problem.validation`; `inputs` are the measured
// channels the model replays, `roles` those that carry the power and the deflection. The
// temperature is the model's, where it publishes one.
ResidualDiagnostics diagnose(const FitProblem& problem, const std::vector<double>& values,
                             const std::vector<std::string>& inputs,
                             const MeasuredRoles& roles = {});

// The diagnostic that should give a named effect away, read from `diagnostics`: "corr(r,
// last direction of motion) = 0.41 (white: |.| < 0.03); loop ~ f^0.05".
std::string signature_evidence(const std::string& effect, const ResidualDiagnostics& diagnostics,
                               const FitProblem& problem);

// What the residual of `output` follows, strongest first: each feature's correlation, each
// input's cross-correlation peak and the drift, with its strength as a multiple of what white
// noise reaches (1: the 95 % bound). What `unexplained` reports in place of an effect.
struct SignatureStrength {
  std::string what;  // "corr(r, last direction of motion) = -0.58"
  double strength = 0.0;
};
std::vector<SignatureStrength> ranked_signatures(const ResidualDiagnostics& diagnostics,
                                                 std::size_t output);

}  // namespace tcpmsim::fit
