#include "identification/discovery.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <numeric>

#include "identification/candidate_aliases.h"
#include "identification/discovery_diagnostics.h"
#include "identification/discovery_setup.h"
#include "identification/model_order.h"
#include "identification/residual_diagnostics.h"
#include "kinds/standard_kinds.h"
#include "sim/not_a_number.h"
#include "sim/parallel_rounds.h"
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
  bool misses_an_output = false;  // by more than the noise floor (its margin included)
};

Baseline baseline_of(FitSpec spec, FitResult result, const std::vector<double>& noise,
                     const DiscoverSetup& setup) {
  Baseline base;
  const auto at_noise =
      at_noise_floor(result.validation.rmse, setup.floor, setup.request.floor_margin);
  base.misses_an_output = std::find(at_noise.begin(), at_noise.end(), false) != at_noise.end();
  base.bic = bic(result.identification, result.estimates.size());
  base.validation = simulate_outputs(spec.problem, values_of(result), spec.problem.validation);
  base.combined_rmse = combined_rmse(result.validation.rmse, noise);
  base.spec = std::move(spec);
  base.result = std::move(result);
  return base;
}

void score(CandidateOutcome& outcome, const Baseline& base, const std::vector<double>& noise,
           const std::vector<std::vector<double>>& measured, const DiscoverSetup& setup) {
  const DiscoverRequest& request = setup.request;
  const FitResult& result = outcome.result;
  outcome.validation_rmse = result.validation.rmse;
  outcome.gap_shrink = 1.0 - combined_rmse(result.validation.rmse, noise) / base.combined_rmse;
  const auto augmented =
      simulate_outputs(outcome.spec.problem, values_of(result), outcome.spec.problem.validation);
  // The noise's colour, from what the candidate leaves of data no fit has seen: a load cell's
  // filter or a drift makes neighbouring samples alike, and counted as independent they would
  // make any candidate that follows a little of that noise significant.
  const auto left = difference(measured, augmented);
  outcome.residual_autocorrelation.clear();
  outcome.evidence_shares.clear();
  for (const auto& series : left) {
    outcome.residual_autocorrelation.push_back(autocorrelation(series, 1)[1]);
    outcome.evidence_shares.push_back(evidence_share(series));
  }
  outcome.delta_bic =
      bic_change(result.identification, result.estimates.size(), base.result.identification,
                 base.result.estimates.size(), outcome.evidence_shares);
  outcome.bic = base.bic + outcome.delta_bic;
  // Does what the effect changes look like what the base model missed? The matched filter's
  // statistic, standard normal when the residual is noise alone: its variance grows by
  // 1 / share for noise of that colour.
  const auto change = difference(augmented, base.validation);
  const auto residual = difference(measured, base.validation);
  double change_norm = 0.0, coloured_norm = 0.0;
  for (std::size_t k = 0; k < change.size(); ++k) {
    const double power = weighted_dot({change[k]}, {change[k]}, {noise[k]});
    change_norm += power;
    coloured_norm += power / outcome.evidence_shares[k];
  }
  change_norm = std::sqrt(change_norm);
  coloured_norm = std::sqrt(coloured_norm);
  const double residual_norm = std::sqrt(weighted_dot(residual, residual, noise));
  const double projection = weighted_dot(change, residual, noise);
  outcome.signature_match =
      change_norm * residual_norm > 0 ? projection / (change_norm * residual_norm) : 0.0;
  outcome.signature_z = coloured_norm > 0 ? projection / coloured_norm : 0.0;
  outcome.validation_change = change;
  // An effect that closes only a sliver of the gap above the noise floor is not what is
  // missing, however significant its BIC: where the base model misses an output, naming it
  // would hide the rest; where it is at the floor, it names a trace of the model's own misfit.
  outcome.gap_closed =
      above_noise_gap_closed(base.result.validation.rmse, result.validation.rmse, setup.floor);
  outcome.missed_gap_closed = missed_gap_closed(base.result.validation.rmse, result.validation.rmse,
                                                setup.floor, request.floor_margin);
  outcome.significant =
      outcome.delta_bic < -request.bic_threshold && outcome.gap_shrink > request.min_gap_shrink &&
      outcome.signature_z >= request.min_signature &&
      closes_enough_of_gap(base.result.validation.rmse, result.validation.rmse, setup.floor,
                           request.floor_margin, request.min_gap_closed);
}

void rank(std::vector<CandidateOutcome>& candidates) {
  std::stable_sort(candidates.begin(), candidates.end(), [](const auto& a, const auto& b) {
    const auto key = [](const CandidateOutcome& c) {
      const int group = c.status != "fitted" ? 3 : c.superseded ? 2 : c.significant ? 0 : 1;
      return std::make_pair(group, c.status == "fitted" ? c.delta_bic : 0.0);
    };
    return key(a) < key(b);
  });
}

// Adds `earlier`'s effort to `result`'s.
void count_effort(FitResult& result, const FitResult& earlier) {
  result.simulations += earlier.simulations;
  result.iterations += earlier.iterations;
}

// The refit of `problem` from its best drawn start, as a probe of a few iterations first: only
// if that has gone below `to_beat` (the refit from the nested start) is it refined on, to the
// iterations `settings` allow. Most candidates the data do not hold never get there, and
// refining each to the iteration limit was most of the retry's cost. (Probing every drawn start
// helps where the base fit has absorbed the effect, a fan taken into a higher hA, whose draw
// nearest zero size falls back to zero: on a hanging mass under a ratchet and a fan the fan's
// refit lowered the BIC by 65 from the other draws. It cost the benchmark 1439 runs against
// 899, 139.5 s against 113 s, over its two-minute bar, so it is not done.)
FitResult refit_from_drawn_start(const FitProblem& problem, const FitSettings& settings,
                                 double to_beat) {
  constexpr int kProbeIterations = 10;
  FitSettings probe = settings;
  probe.drawn_starts_only = true;
  probe.max_iterations = std::min(settings.max_iterations, kProbeIterations);
  FitResult probed = fit_model(problem, probe);
  if (probed.converged || probed.cost >= to_beat || probe.max_iterations >= settings.max_iterations)
    return probed;
  FitSettings onward = settings;
  onward.starts = 0;
  onward.start = values_of(probed);
  // The iterations the probe left (it used them all: it did not converge).
  onward.max_iterations = settings.max_iterations - probe.max_iterations;
  FitResult refined = fit_model(problem, onward);
  count_effort(refined, probed);
  refined.start_cost = probed.start_cost;
  refined.refined_start = probed.refined_start;
  return refined;
}

// A refit from the nested start that never left it: at zero size an effect's shape parameters
// (a knee's position and sharpness, a time constant) change nothing, so their gradient is zero
// and Levenberg-Marquardt grows the size, if at all, in the shape it started with. The best
// drawn start is then refined too, and the lower of the two kept. "Never left": the cost fell
// by less than half a unit (one unit of chi-squared), far below any significant BIC change. Only
// where the base model misses some output by more than the noise (`gap`): where it fits every
// output to the noise, there is no gap for the effect to close, and on such data every
// candidate finds nothing and would try again (1.6 times the simulations).
void retry_from_drawn_start(CandidateOutcome& outcome, const FitSettings& settings, bool gap) {
  const FitResult& first = outcome.result;
  if (!gap || settings.starts == 0 || first.refined_start != 0 ||
      first.cost < outcome.nested_cost - 0.5)
    return;
  outcome.retried_from_drawn = true;
  FitResult again;
  try {
    again = refit_from_drawn_start(outcome.spec.problem, settings, first.cost);
  } catch (const FitFailure&) {
    return;  // no drawn start could be simulated: the first refit stands
  }
  outcome.drawn_kept = again.cost < first.cost;
  if (outcome.drawn_kept) {
    count_effort(again, first);
    outcome.result = std::move(again);
  } else {
    count_effort(outcome.result, again);
  }
}

// The refit of a candidate whose problem and settings (its nested start first) are in
// `outcome.spec`, from the best multistart point; again from the best drawn start when that was
// the nested start, the fit never left it and the base model leaves a `gap`; again from the
// nested start alone when the fit ended above it.
void refit_nested(CandidateOutcome& outcome, const FitSettings& settings, bool gap) {
  const FitProblem& problem = outcome.spec.problem;
  outcome.result = fit_model(problem, settings);
  outcome.nested_cost = outcome.result.start_cost;
  retry_from_drawn_start(outcome, settings, gap);
  const auto above_nested = [&](const FitResult& result) {
    return result.cost > outcome.nested_cost * (1.0 + 1e-9);
  };
  if (above_nested(outcome.result)) {
    FitSettings continuation = settings;
    continuation.starts = 0;
    continuation.max_iterations = 2 * settings.max_iterations;
    FitResult again = fit_model(problem, continuation);
    count_effort(again, outcome.result);
    outcome.result = std::move(again);
    outcome.retried = true;
  }
  outcome.status = above_nested(outcome.result) ? "failed" : "fitted";
  if (outcome.status == "failed")
    outcome.reason = "the refit ended above its nested start (cost " +
                     number_text(outcome.result.cost, 8) + " against " +
                     number_text(outcome.nested_cost, 8) +
                     ") also from zero size: a solver failure, not evidence";
}

// The candidate refit: the base parameters (at the base estimates, same bounds) and the
// effect's, starting where the effect has zero size (the base model: its nested start), its
// multistart drawing the effect's only. A refit that ends above its nested start went the wrong
// way from a drawn start: it is fitted again from the nested start alone (continuation from
// zero size, more iterations), and if that still ends above, it failed; it is never evidence
// against the effect.
CandidateOutcome fit_candidate(const DiscoverSetup& setup, const Baseline& baseline,
                               const std::vector<double>& noise, const EffectCandidate& candidate) {
  const FitResult& base = baseline.result;
  const auto started = std::chrono::steady_clock::now();
  CandidateOutcome outcome;
  outcome.name = candidate.name;
  outcome.member = candidate.member;
  outcome.order = candidate.order;
  outcome.description = candidate.description;
  outcome.signature = candidate.signature;
  try {
    outcome.spec = respecified(setup, base.estimates, candidate.overrides);
    auto& problem = outcome.spec.problem;
    for (std::size_t k = 0; k < noise.size(); ++k) problem.outputs[k].noise = noise[k];
    problem.parameters.insert(problem.parameters.end(), candidate.parameters.begin(),
                              candidate.parameters.end());
    auto& settings = outcome.spec.settings;
    settings.start = values_of(base);
    settings.start.insert(settings.start.end(), candidate.nested.begin(), candidate.nested.end());
    // The candidates run in parallel, each on one thread, its sensitivities in one run (the
    // cheapest on one thread).
    settings.threads = 1;
    settings.sensitivity_groups = 1;
    settings.screened_from = base.estimates.size();
    settings.starts = std::min(settings.starts, 4);
    settings.refine = 1;
    settings.max_iterations = 30;
    // The cost is about half the sample count (some 10^4 here); a relative 1e-6 is 0.01 of it,
    // far below the BIC's unit, at which the ranking is decided.
    settings.function_tolerance = 1e-6;
    refit_nested(outcome, settings, baseline.misses_an_output);
  } catch (const std::exception& error) {
    outcome.status = "failed";
    outcome.reason = error.what();
  }
  outcome.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return outcome;
}

// The catalogue's candidates refitted from `baseline` and scored against it, each fit on one
// thread: every family's simplest members (order 1), then the higher orders of the families
// they gave evidence for (forward selection of the model order: a Prandtl-Ishlinskii operator
// is tried where one Dahl element already explains something; higher_orders_to_try). A thread
// that would idle at the end of the first round starts the higher orders the members finished
// so far point to, and so does one as soon as the families that have higher orders have scored
// their simplest members (run_two_rounds); what is tried and reported is the same on any
// number of threads. The outcomes are the simplest members in the catalogue's order, then the
// higher orders tried.
std::vector<CandidateOutcome> fit_catalogue(const DiscoverSetup& setup, const Baseline& baseline,
                                            const std::vector<double>& noise,
                                            const std::vector<std::vector<double>>& measured,
                                            const std::vector<EffectCandidate>& tried,
                                            int& simulations) {
  std::vector<CandidateOutcome> fitted(tried.size());
  const auto fit_and_score = [&](std::size_t k) {
    fitted[k] = fit_candidate(setup, baseline, noise, tried[k]);
    if (fitted[k].status == "fitted") score(fitted[k], baseline, noise, measured, setup);
  };
  // The simplest members of families with higher orders lead: the higher orders they point to
  // start as soon as they are scored, beside the other families' simplest members.
  const std::vector<FamilyMembers> families = families_of(tried);
  std::vector<std::size_t> leading, others;
  for (const auto& family : families) {
    auto& into = family.higher.empty() ? others : leading;
    into.insert(into.end(), family.simplest.begin(), family.simplest.end());
  }
  std::vector<std::size_t> simplest = longest_first(leading, tried);
  for (const std::size_t k : longest_first(others, tried)) simplest.push_back(k);
  const auto higher_orders = [&](const std::vector<char>& finished) {
    return higher_orders_to_try(families, tried, fitted, finished, setup.request.bic_threshold);
  };
  std::vector<char> reported(tried.size(), 0);
  for (const std::size_t k : simplest) reported[k] = 1;
  for (const std::size_t k : run_two_rounds(simplest, leading.size(), higher_orders, tried.size(),
                                            setup.request.threads, fit_and_score))
    reported[k] = 1;
  std::vector<CandidateOutcome> outcomes;
  for (const bool first_round : {true, false}) {
    for (std::size_t k = 0; k < tried.size(); ++k) {
      if (!reported[k] || (tried[k].order == 1) != first_round) continue;
      simulations += fitted[k].result.simulations;
      outcomes.push_back(std::move(fitted[k]));
    }
  }
  return outcomes;
}

// Only the best member of a family (lowest BIC) competes for the verdict: the family's model
// order is chosen by the same criterion as the effect.
void choose_members(std::vector<CandidateOutcome>& outcomes) {
  for (auto& outcome : outcomes) {
    outcome.superseded = false;
    if (outcome.status != "fitted") continue;
    for (const auto& other : outcomes) {
      if (&other == &outcome || other.status != "fitted" || other.name != outcome.name) continue;
      if (other.bic < outcome.bic || (other.bic == outcome.bic && other.order < outcome.order))
        outcome.superseded = true;
    }
  }
}

}  // namespace

const char* verdict_kind_name(VerdictKind kind) {
  switch (kind) {
    case VerdictKind::effect:
      return "effect";
    case VerdictKind::none:
      return "none";
    case VerdictKind::unexplained:
      break;
  }
  return "unexplained";
}

std::vector<bool> at_noise_floor(const std::vector<double>& rmse, const std::vector<double>& floor,
                                 double margin) {
  std::vector<bool> at_noise;
  for (std::size_t k = 0; k < floor.size(); ++k)
    at_noise.push_back(rmse[k] <= (1.0 + margin) * floor[k]);
  return at_noise;
}

double structured_rms(double rmse, double floor) {
  return std::sqrt(std::max(0.0, rmse * rmse - floor * floor));
}

double above_noise_gap_closed(const std::vector<double>& base_rmse,
                              const std::vector<double>& augmented_rmse,
                              const std::vector<double>& floor) {
  const double base = combined_rmse(base_rmse, floor);
  if (!(base > 1.0)) return kNaN;
  return (base - combined_rmse(augmented_rmse, floor)) / (base - 1.0);
}

double missed_gap_closed(const std::vector<double>& base_rmse,
                         const std::vector<double>& augmented_rmse,
                         const std::vector<double>& floor, double margin) {
  std::vector<double> base, augmented, missed_floor;
  const auto at_noise = at_noise_floor(base_rmse, floor, margin);
  for (std::size_t k = 0; k < floor.size(); ++k) {
    if (at_noise[k]) continue;
    base.push_back(base_rmse[k]);
    augmented.push_back(augmented_rmse[k]);
    missed_floor.push_back(floor[k]);
  }
  return base.empty() ? kNaN : above_noise_gap_closed(base, augmented, missed_floor);
}

bool closes_enough_of_gap(const std::vector<double>& base_rmse,
                          const std::vector<double>& augmented_rmse,
                          const std::vector<double>& floor, double margin, double min_share) {
  double share = missed_gap_closed(base_rmse, augmented_rmse, floor, margin);
  if (std::isnan(share)) share = above_noise_gap_closed(base_rmse, augmented_rmse, floor);
  return std::isnan(share) || share >= min_share;
}

double combined_rmse(const std::vector<double>& rmse, const std::vector<double>& noise) {
  double sum = 0.0;
  for (std::size_t k = 0; k < rmse.size(); ++k) sum += std::pow(rmse[k] / noise[k], 2);
  return std::sqrt(sum / static_cast<double>(rmse.size()));
}

double evidence_share(std::span<const double> residual) {
  if (residual.size() < 3) return 1.0;
  const double rho = std::clamp(autocorrelation(residual, 1)[1], 0.0, 0.99);
  return (1.0 - rho) / (1.0 + rho);
}

double bic_change(const WindowScore& candidate, std::size_t parameters, const WindowScore& base,
                  std::size_t base_parameters, const std::vector<double>& shares) {
  const double n = static_cast<double>(candidate.samples);
  const auto log_rss = [](double rmse) {
    return std::log(std::max(rmse * rmse, std::numeric_limits<double>::min()));
  };
  double value = 0.0;
  for (std::size_t k = 0; k < candidate.rmse.size(); ++k)
    value += shares[k] * n * (log_rss(candidate.rmse[k]) - log_rss(base.rmse[k]));
  const double total = n * static_cast<double>(candidate.rmse.size());
  return value +
         (static_cast<double>(parameters) - static_cast<double>(base_parameters)) * std::log(total);
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
  // Its cost in the weights the candidates are fitted with (a single output keeps the first
  // stage's fit, whose cost was in the first weights), so that each candidate's is comparable.
  base.cost = 0.0;
  for (std::size_t k = 0; k < noise.size(); ++k)
    base.cost += 0.5 * static_cast<double>(base.identification.samples) *
                 std::pow(base.identification.rmse[k] / noise[k], 2);
  for (std::size_t k = 0; k < noise.size(); ++k) spec.problem.outputs[k].noise = noise[k];
  Baseline baseline = baseline_of(spec, base, noise, setup);
  const auto measured = measured_outputs(spec.problem, spec.problem.validation);

  // The candidates, fitted in parallel.
  Context fitted = spec.problem.model->make_context();
  for (const auto& estimate : base.estimates) fitted.set_parameter(estimate.path, estimate.value);
  std::vector<std::string> model_outputs;
  for (const auto& output : spec.problem.outputs) model_outputs.push_back(output.output);
  // How warm the fitted base model runs: a ratchet's threshold starts where it is crossed.
  CatalogueContext context{setup.roles, 0.0};
  const auto& times = spec.problem.data->time();
  const std::vector<double> temperature =
      model_temperature(spec.problem, values_of(base), {times.front(), times.back()});
  if (!temperature.empty())
    context.temperature_peak = *std::max_element(temperature.begin(), temperature.end());
  Candidates catalogue =
      effect_candidates(*spec.problem.model, fitted, *spec.problem.data, model_outputs, context);
  const auto& wanted = setup.request.effects;
  std::vector<EffectCandidate> tried;
  const int max_order = setup.request.max_order;
  for (auto& candidate : catalogue.candidates) {
    if ((wanted.empty() ||
         std::find(wanted.begin(), wanted.end(), candidate.name) != wanted.end()) &&
        (max_order <= 0 || candidate.order <= max_order))
      tried.push_back(std::move(candidate));
  }
  for (auto& skipped : catalogue.skipped) {
    if (wanted.empty() || std::find(wanted.begin(), wanted.end(), skipped.name) != wanted.end())
      discovery.skipped.push_back(std::move(skipped));
  }
  std::vector<CandidateOutcome> outcomes =
      fit_catalogue(setup, baseline, noise, measured, tried, simulations);
  choose_members(outcomes);
  rank(outcomes);

  // Re-tuning is not an effect: refit the base model from where the best candidate left its
  // parameters. If that alone lowers the base cost by more than half a unit (one in the BIC),
  // the base fit had stopped short, and every candidate is fitted again from the better base,
  // so that each still nests the base it is judged against.
  if (!outcomes.empty() && outcomes.front().status == "fitted" && outcomes.front().significant) {
    std::vector<ParameterEstimate> start(
        outcomes.front().result.estimates.begin(),
        outcomes.front().result.estimates.begin() + static_cast<long>(base.estimates.size()));
    FitSpec retuned_spec = respecified(setup, start, {});
    for (std::size_t k = 0; k < noise.size(); ++k) retuned_spec.problem.outputs[k].noise = noise[k];
    FitResult retuned = fit_base(retuned_spec, 0);
    simulations += retuned.simulations;
    if (retuned.cost < baseline.result.cost - 0.5) {
      baseline = baseline_of(retuned_spec, retuned, noise, setup);
      outcomes = fit_catalogue(setup, baseline, noise, measured, tried, simulations);
      choose_members(outcomes);
      rank(outcomes);
      discovery.base_rounds = 2;
    }
  }

  // Of candidates the data do not tell apart, the commonest effect is named.
  name_first_of_aliases(outcomes, noise, setup.request.bic_threshold,
                        setup.request.alias_correlation, effect_names());

  discovery.base = baseline.result;
  discovery.setup.base = baseline.spec;
  discovery.base_bic = baseline.bic;
  discovery.noise = noise;
  discovery.diagnostics = diagnose(baseline.spec.problem, values_of(baseline.result),
                                   setup.request.inputs, setup.roles);
  for (auto& outcome : outcomes) {
    if (outcome.status == "fitted")
      outcome.signature_evidence =
          signature_evidence(outcome.name, discovery.diagnostics, baseline.spec.problem);
  }
  discovery.candidates = std::move(outcomes);
  discovery.at_noise =
      at_noise_floor(discovery.base.validation.rmse, setup.floor, setup.request.floor_margin);
  const bool named = !discovery.candidates.empty() &&
                     discovery.candidates.front().status == "fitted" &&
                     discovery.candidates.front().significant;
  const bool at_noise =
      std::all_of(discovery.at_noise.begin(), discovery.at_noise.end(), [](bool at) { return at; });
  discovery.kind = named      ? VerdictKind::effect
                   : at_noise ? VerdictKind::none
                              : VerdictKind::unexplained;
  discovery.verdict = named ? discovery.candidates.front().name : verdict_kind_name(discovery.kind);
  discovery.gap_closed =
      named ? above_noise_gap_closed(discovery.base.validation.rmse,
                                     discovery.candidates.front().validation_rmse, setup.floor)
            : (at_noise ? kNaN : 0.0);
  discovery.simulations = simulations;
  discovery.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return discovery;
}

}  // namespace tcpmsim::fit
