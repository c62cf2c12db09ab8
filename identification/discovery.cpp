#include "identification/discovery.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <numeric>

#include "identification/discovery_setup.h"
#include "kinds/standard_kinds.h"
#include "sim/parallel_runs.h"
#include "sim/value_check.h"

namespace tcpmsim::fit {

namespace {

std::vector<double> values_of(const FitResult& result) {
  std::vector<double> values;
  for (const auto& estimate : result.estimates) values.push_back(estimate.value);
  return values;
}

// `spec` with its model rebuilt from the discover overrides, the base estimates written in
// (so the model starts where the base fit ended) and `extra` overrides.
FitSpec respecified(const DiscoverSetup& setup, const std::vector<ParameterEstimate>& start,
                    const std::vector<std::string>& extra) {
  std::vector<std::string> overrides = setup.overrides;
  for (const auto& estimate : start)
    overrides.push_back(estimate.path + "=" + number_text(estimate.value, 17) + " " +
                        (estimate.unit == "1" ? "" : estimate.unit));
  overrides.insert(overrides.end(), extra.begin(), extra.end());
  FitSpec spec = setup.base;
  spec.problem.model = std::make_shared<const Scenario>(
      load_scenario(setup.base.model_file, overrides, setup.units));
  return spec;
}

// sum_k sum_i a_k[i] b_k[i] / noise_k^2.
double weighted_dot(const std::vector<std::vector<double>>& a,
                    const std::vector<std::vector<double>>& b, const std::vector<double>& noise) {
  double sum = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    for (std::size_t i = 0; i < a[k].size(); ++i) sum += a[k][i] * b[k][i] / (noise[k] * noise[k]);
  }
  return sum;
}

std::vector<std::vector<double>> difference(const std::vector<std::vector<double>>& a,
                                            const std::vector<std::vector<double>>& b) {
  auto result = a;
  for (std::size_t k = 0; k < a.size(); ++k) {
    for (std::size_t i = 0; i < a[k].size(); ++i) result[k][i] -= b[k][i];
  }
  return result;
}

// The fit of the base model from `spec`'s starting values, with the discover settings.
FitResult fit_base(const FitSpec& spec, int starts) {
  FitSettings settings = spec.settings;
  settings.starts = starts;
  return fit_model(spec.problem, settings);
}

// The base model's simulated outputs in the validation window at its estimates.
struct Baseline {
  FitSpec spec;
  FitResult result;
  double bic = 0.0;
  std::vector<std::vector<double>> validation;  // simulated
  double combined_rmse = 0.0;
};

Baseline baseline_of(FitSpec spec, FitResult result, const std::vector<double>& noise) {
  Baseline base;
  base.bic = bic(result.identification, result.estimates.size());
  base.validation = simulate_outputs(spec.problem, values_of(result), spec.problem.validation);
  base.combined_rmse = combined_rmse(result.validation.rmse, noise);
  base.spec = std::move(spec);
  base.result = std::move(result);
  return base;
}

void score(CandidateOutcome& outcome, const Baseline& base, const std::vector<double>& noise,
           const std::vector<std::vector<double>>& measured, const DiscoverRequest& request) {
  const FitResult& result = outcome.result;
  outcome.bic = bic(result.identification, result.estimates.size());
  outcome.delta_bic = outcome.bic - base.bic;
  outcome.validation_rmse = result.validation.rmse;
  outcome.gap_shrink = 1.0 - combined_rmse(result.validation.rmse, noise) / base.combined_rmse;
  // Does what the effect changes look like what the base model missed?
  const auto augmented =
      simulate_outputs(outcome.spec.problem, values_of(result), outcome.spec.problem.validation);
  const auto change = difference(augmented, base.validation);
  const auto residual = difference(measured, base.validation);
  const double change_norm = std::sqrt(weighted_dot(change, change, noise));
  const double residual_norm = std::sqrt(weighted_dot(residual, residual, noise));
  const double projection = weighted_dot(change, residual, noise);
  outcome.signature_match =
      change_norm * residual_norm > 0 ? projection / (change_norm * residual_norm) : 0.0;
  outcome.signature_z = change_norm > 0 ? projection / change_norm : 0.0;
  outcome.significant = outcome.delta_bic < -request.bic_threshold &&
                        outcome.gap_shrink > request.min_gap_shrink &&
                        outcome.signature_z >= request.min_signature;
}

void rank(std::vector<CandidateOutcome>& candidates) {
  std::stable_sort(candidates.begin(), candidates.end(), [](const auto& a, const auto& b) {
    const auto key = [](const CandidateOutcome& c) {
      return std::make_pair(c.status == "fitted" ? (c.significant ? 0 : 1) : 2,
                            c.status == "fitted" ? c.delta_bic : 0.0);
    };
    return key(a) < key(b);
  });
}

// The candidate refit: the base parameters (at the base estimates, same bounds) and the
// effect's, its multistart drawing the effect's only.
CandidateOutcome fit_candidate(const DiscoverSetup& setup, const FitResult& base,
                               const std::vector<double>& noise, const EffectCandidate& candidate) {
  const auto started = std::chrono::steady_clock::now();
  CandidateOutcome outcome;
  outcome.name = candidate.name;
  outcome.description = candidate.description;
  outcome.signature = candidate.signature;
  try {
    outcome.spec = respecified(setup, base.estimates, candidate.overrides);
    auto& problem = outcome.spec.problem;
    for (std::size_t k = 0; k < noise.size(); ++k) problem.outputs[k].noise = noise[k];
    problem.parameters.insert(problem.parameters.end(), candidate.parameters.begin(),
                              candidate.parameters.end());
    auto& settings = outcome.spec.settings;
    settings.threads = 1;  // the candidates run in parallel
    settings.screened_from = base.estimates.size();
    settings.starts = std::min(settings.starts, 4);
    settings.refine = 1;
    settings.max_iterations = 30;
    // The cost is about half the sample count (some 10^4 here); a relative 1e-6 is 0.01 of it,
    // far below the BIC's unit, at which the ranking is decided.
    settings.function_tolerance = 1e-6;
    outcome.result = fit_model(problem, settings);
    outcome.status = "fitted";
  } catch (const std::exception& error) {
    outcome.status = "failed";
    outcome.reason = error.what();
  }
  outcome.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return outcome;
}

}  // namespace

double combined_rmse(const std::vector<double>& rmse, const std::vector<double>& noise) {
  double sum = 0.0;
  for (std::size_t k = 0; k < rmse.size(); ++k) sum += std::pow(rmse[k] / noise[k], 2);
  return std::sqrt(sum / static_cast<double>(rmse.size()));
}

double bic(const WindowScore& identification, std::size_t parameters) {
  const double n = static_cast<double>(identification.samples);
  double value = 0.0;
  for (double rmse : identification.rmse)
    value += n * std::log(std::max(rmse * rmse, std::numeric_limits<double>::min()));
  const double total = n * static_cast<double>(identification.rmse.size());
  return value + static_cast<double>(parameters) * std::log(total);
}

Discovery discover(const DiscoverSetup& setup) {
  const auto started = std::chrono::steady_clock::now();
  Discovery discovery;
  discovery.setup = setup;
  int simulations = 0;

  // The base fit, weighted first by the residuals at the model's own values, then by its own.
  FitSpec spec = setup.base;
  std::vector<double> noise = initial_noise(spec.problem);
  for (std::size_t k = 0; k < noise.size(); ++k) spec.problem.outputs[k].noise = noise[k];
  FitResult base = fit_base(spec, spec.settings.starts);
  int base_simulations = base.simulations;
  noise = base.identification.rmse;
  for (double& sigma : noise) sigma = sigma > 0 ? sigma : 1.0;
  if (noise.size() > 1) {
    spec = respecified(setup, base.estimates, {});
    for (std::size_t k = 0; k < noise.size(); ++k) spec.problem.outputs[k].noise = noise[k];
    base = fit_base(spec, 0);
    base_simulations += base.simulations;
  }
  base.simulations = base_simulations;  // both stages
  simulations += base_simulations;
  for (std::size_t k = 0; k < noise.size(); ++k) spec.problem.outputs[k].noise = noise[k];
  Baseline baseline = baseline_of(spec, base, noise);
  const auto measured = measured_outputs(spec.problem, spec.problem.validation);

  // The candidates, fitted in parallel.
  Context fitted = spec.problem.model->make_context();
  for (const auto& estimate : base.estimates) fitted.set_parameter(estimate.path, estimate.value);
  std::vector<std::string> model_outputs;
  for (const auto& output : spec.problem.outputs) model_outputs.push_back(output.output);
  Candidates catalogue =
      effect_candidates(*spec.problem.model, fitted, *spec.problem.data, model_outputs);
  const auto& wanted = setup.request.effects;
  std::vector<EffectCandidate> tried;
  for (auto& candidate : catalogue.candidates) {
    if (wanted.empty() || std::find(wanted.begin(), wanted.end(), candidate.name) != wanted.end())
      tried.push_back(std::move(candidate));
  }
  for (auto& skipped : catalogue.skipped) {
    if (wanted.empty() || std::find(wanted.begin(), wanted.end(), skipped.name) != wanted.end())
      discovery.skipped.push_back(std::move(skipped));
  }
  std::vector<CandidateOutcome> outcomes(tried.size());
  const std::vector<std::string> labels(tried.size(), "candidate");
  run_in_parallel(labels, setup.request.threads, [&](std::size_t c) {
    outcomes[c] = fit_candidate(setup, base, noise, tried[c]);
  });
  for (auto& outcome : outcomes) {
    if (outcome.status != "fitted") continue;
    simulations += outcome.result.simulations;
    score(outcome, baseline, noise, measured, setup.request);
  }
  rank(outcomes);

  // Re-tuning is not an effect: refit the base model from where the best candidate left its
  // parameters; if that alone does as well, the base fit had stopped short, and every
  // candidate is judged again against the better base.
  for (int round = 0; round < 2 && !outcomes.empty() && outcomes.front().significant; ++round) {
    std::vector<ParameterEstimate> start(
        outcomes.front().result.estimates.begin(),
        outcomes.front().result.estimates.begin() + static_cast<long>(base.estimates.size()));
    FitSpec retuned_spec = respecified(setup, start, {});
    for (std::size_t k = 0; k < noise.size(); ++k) retuned_spec.problem.outputs[k].noise = noise[k];
    FitResult retuned = fit_base(retuned_spec, 0);
    simulations += retuned.simulations;
    if (!(retuned.cost < baseline.result.cost * (1 - 1e-9))) break;
    baseline = baseline_of(retuned_spec, retuned, noise);
    for (auto& outcome : outcomes) {
      if (outcome.status == "fitted") score(outcome, baseline, noise, measured, setup.request);
    }
    rank(outcomes);
  }

  discovery.base = baseline.result;
  discovery.setup.base = baseline.spec;
  discovery.base_bic = baseline.bic;
  discovery.noise = noise;
  discovery.diagnostics =
      diagnose(baseline.spec.problem, values_of(baseline.result), setup.request.inputs);
  for (auto& outcome : outcomes) {
    if (outcome.status == "fitted")
      outcome.signature_evidence =
          signature_evidence(outcome.name, discovery.diagnostics, baseline.spec.problem);
  }
  discovery.candidates = std::move(outcomes);
  discovery.verdict = !discovery.candidates.empty() && discovery.candidates.front().significant
                          ? discovery.candidates.front().name
                          : "none";
  discovery.simulations = simulations;
  discovery.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return discovery;
}

}  // namespace tcpmsim::fit
