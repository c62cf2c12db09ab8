#include "identification/discovery_report.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <sstream>

#include "identification/fit_report.h"
#include "identification/json_numbers.h"
#include "sim/io/hdf5_writer.h"
#include "sim/value_check.h"

namespace tcpmsim::fit {

namespace {

const FitProblem& problem_of(const Discovery& discovery) {
  return discovery.setup.base.problem;
}

// The verdict's outcome, or null.
const CandidateOutcome* verdict_of(const Discovery& discovery) {
  if (discovery.kind != VerdictKind::effect) return nullptr;
  return &discovery.candidates.front();
}

// Whether an output's base validation residual passes Ljung-Box at the 1 % level.
bool residual_white(const Discovery& discovery, std::size_t output) {
  return discovery.diagnostics.outputs[output].whiteness.p_value >= 0.01;
}

nlohmann::json per_output_json(const Discovery& discovery, const std::vector<double>& values) {
  nlohmann::json json = nlohmann::json::object();
  const auto& outputs = problem_of(discovery).outputs;
  for (std::size_t k = 0; k < values.size(); ++k)
    json[outputs[k].channel] = number_or_null(values[k]);
  return json;
}

nlohmann::json estimates_json(const FitResult& result) {
  nlohmann::json json = nlohmann::json::array();
  for (const auto& estimate : result.estimates) {
    json.push_back({{"path", estimate.path},
                    {"unit", estimate.unit},
                    {"estimate", estimate.value},
                    {"standard_error", number_or_null(estimate.standard_error)}});
  }
  return json;
}

nlohmann::json diagnostics_json(const ResidualDiagnostics& diagnostics) {
  nlohmann::json json = nlohmann::json::object();
  json["white_noise_bound"] = diagnostics.bound;
  json["bands_hz"] = diagnostics.bands;
  for (const auto& output : diagnostics.outputs) {
    nlohmann::json entry;
    entry["ljung_box"] = {{"lags", output.whiteness.lags},
                          {"statistic", output.whiteness.statistic},
                          {"p_value", output.whiteness.p_value}};
    entry["drift"] = {{"slope", output.drift.slope},
                      {"standard_error", output.drift.standard_error},
                      {"t", output.drift.t_statistic}};
    entry["band_share"] = output.band_share;
    for (const auto& [input, cross] : output.inputs)
      entry["input_cross_correlation"][input] = {
          {"peak", cross.peak}, {"peak_lag_samples", cross.peak_lag}, {"bound", cross.bound}};
    for (const auto& [feature, value] : output.features)
      entry["feature_correlation"][feature] = number_or_null(value);
    entry["loop"] = {{"frequency_hz", output.loop.frequency},
                     {"quadrature", output.loop.quadrature},
                     {"exponent", number_or_null(output.loop.exponent)}};
    json["outputs"][output.channel] = entry;
  }
  return json;
}

FitSpec spec_for_yaml(const FitSpec& spec, const std::string& data_file) {
  FitSpec copy = spec;
  copy.file.clear();
  copy.data_file = data_file;
  return copy;
}

std::string text(double value, int digits = 3) {
  return number_text(value, digits);
}

// Under a verdict of none: the best candidate, when the BIC favours it but it closes less of the
// gap the base model leaves above the floor than a named effect must (--min-gap-closed), so
// that its delta BIC in the table is not read as a missed effect.
void write_sliver_at_floor(std::ostream& out, const Discovery& discovery) {
  if (discovery.candidates.empty()) return;
  const CandidateOutcome& best = discovery.candidates.front();
  const auto& request = discovery.setup.request;
  if (best.status != "fitted" || best.significant || !(best.delta_bic < -request.bic_threshold) ||
      !(best.gap_closed < request.min_gap_closed))
    return;
  out << "\nThe best candidate, " << best.name << " (" << best.member << "), lowers the BIC by "
      << text(-best.delta_bic, 3) << " (signature z " << text(best.signature_z, 2)
      << ") but closes " << text(100 * best.gap_closed, 2)
      << " % of the gap the base model leaves above the noise floor, under the "
      << text(100 * request.min_gap_closed) << " % a named effect must close (--min-gap-closed): "
      << "a trace of the model's own misfit, not a missing effect.\n";
}

// Under a verdict of none: the outputs whose residual is not white, with the size of their
// structured part and what it follows, so that none is not read as "the residual is noise".
void write_structured_rest(std::ostream& out, const Discovery& discovery) {
  const auto& outputs = problem_of(discovery).outputs;
  for (std::size_t k = 0; k < outputs.size(); ++k) {
    if (residual_white(discovery, k)) continue;
    const double floor = discovery.setup.floor[k];
    const double rest = structured_rms(discovery.base.validation.rmse[k], floor);
    out << "\nThe " << outputs[k].channel << " residual is not white (Ljung-Box p = "
        << text(discovery.diagnostics.outputs[k].whiteness.p_value, 2)
        << "): a structured part of about " << text(rest, 3) << " " << outputs[k].unit << " RMS ("
        << text(100 * rest / floor, 3)
        << " % of the floor) remains that no candidate explains significantly, below the margin "
           "(--floor-margin) discover is asked to explain. It follows, strongest first: ";
    const auto ranked = ranked_signatures(discovery.diagnostics, k);
    for (std::size_t i = 0; i < std::min<std::size_t>(ranked.size(), 3); ++i)
      out << (i ? "; " : "") << ranked[i].what << " (" << text(ranked[i].strength, 2) << "x)";
    out << ".\n";
  }
}

// The candidates the data do not tell from the verdict's, as a sentence; "" without any.
std::string aliases_text(const CandidateOutcome& verdict) {
  if (verdict.aliases.empty()) return "";
  std::string names;
  for (const auto& alias : verdict.aliases) {
    if (!names.empty()) names += ", ";
    names += alias.name + " (correlation " + text(alias.correlation, 3) + ", delta BIC " +
             text(alias.delta_bic, 3) + ")";
  }
  return " The data do not tell it from " + names +
         ": their changes to the outputs correlate, and no BIC difference reaches the threshold; "
         "the verdict names the first of them in the catalogue's order, the commoner effect.";
}

}  // namespace

std::string outputs_above_floor(const std::vector<FitOutput>& outputs,
                                const std::vector<double>& rmse, const std::vector<double>& floor,
                                double margin) {
  const auto at_noise = at_noise_floor(rmse, floor, margin);
  std::string text;
  for (std::size_t k = 0; k < at_noise.size(); ++k) {
    if (at_noise[k]) continue;
    if (!text.empty()) text += ", ";
    text += outputs[k].channel + " " + number_text(rmse[k] / floor[k], 3) + " times";
  }
  return text;
}

std::string missed_with_effect(const Discovery& discovery) {
  const CandidateOutcome* verdict = verdict_of(discovery);
  if (!verdict) return "";
  return outputs_above_floor(problem_of(discovery).outputs, verdict->validation_rmse,
                             discovery.setup.floor, discovery.setup.request.floor_margin);
}

std::string discovery_json(const Discovery& discovery) {
  nlohmann::json json;
  json["verdict"] = discovery.verdict;
  json["verdict_kind"] = verdict_kind_name(discovery.kind);
  if (const auto* verdict = verdict_of(discovery)) {
    json["member"] = verdict->member;
    json["order"] = verdict->order;
    json["aliases"] = nlohmann::json::array();
    for (const auto& alias : verdict->aliases)
      json["aliases"].push_back({{"effect", alias.name},
                                 {"correlation", alias.correlation},
                                 {"delta_bic", alias.delta_bic}});
  }
  json["model"] = discovery.setup.request.model_file;
  json["data"] = discovery.setup.request.data_file;
  json["ranking"] = nlohmann::json::array();
  for (const auto& candidate : discovery.candidates) {
    nlohmann::json entry = {{"effect", candidate.name},
                            {"member", candidate.member},
                            {"order", candidate.order},
                            {"status", candidate.status},
                            {"nested_cost", candidate.nested_cost},
                            {"retried_from_nested_start", candidate.retried},
                            {"retried_from_drawn_start", candidate.retried_from_drawn},
                            {"drawn_start_kept", candidate.drawn_kept}};
    if (candidate.status == "fitted") {
      entry["cost"] = candidate.result.cost;
      entry["superseded_in_family"] = candidate.superseded;
      entry["delta_bic"] = candidate.delta_bic;
      entry["validation_rmse"] = per_output_json(discovery, candidate.validation_rmse);
      entry["gap_shrink"] = candidate.gap_shrink;
      entry["gap_closed"] = number_or_null(candidate.gap_closed);
      entry["missed_gap_closed"] = number_or_null(candidate.missed_gap_closed);
      entry["signature_match"] = candidate.signature_match;
      entry["signature_z"] = candidate.signature_z;
      entry["residual_autocorrelation"] =
          per_output_json(discovery, candidate.residual_autocorrelation);
      entry["evidence_share"] = per_output_json(discovery, candidate.evidence_shares);
      entry["significant"] = candidate.significant;
      entry["signature"] = candidate.signature;
      entry["evidence"] = candidate.signature_evidence;
      entry["parameters"] = estimates_json(candidate.result);
      entry["simulations"] = candidate.result.simulations;
      entry["iterations"] = candidate.result.iterations;
      entry["gradient"] = candidate.result.gradient;
      entry["seconds"] = candidate.seconds;
      entry["termination"] = candidate.result.termination;
    } else {
      entry["reason"] = candidate.reason;
    }
    json["ranking"].push_back(entry);
  }
  json["skipped"] = nlohmann::json::array();
  for (const auto& skipped : discovery.skipped)
    json["skipped"].push_back({{"effect", skipped.name}, {"reason", skipped.reason}});
  json["baseline"] = {
      {"validation_rmse", per_output_json(discovery, discovery.base.validation.rmse)},
      {"identification_rmse", per_output_json(discovery, discovery.base.identification.rmse)},
      {"bic", discovery.base_bic},
      {"cost", discovery.base.cost},
      {"candidate_rounds", discovery.base_rounds},
      {"simulations", discovery.base.simulations},
      {"gradient", discovery.base.gradient},
      {"parameters", estimates_json(discovery.base)}};
  const CandidateOutcome* verdict = verdict_of(discovery);
  const auto& augmented_rmse = verdict ? verdict->validation_rmse : discovery.base.validation.rmse;
  const auto augmented_at_noise =
      at_noise_floor(augmented_rmse, discovery.setup.floor, discovery.setup.request.floor_margin);
  json["augmented"] = {{"effect", verdict ? nlohmann::json(verdict->name) : nullptr},
                       {"validation_rmse", per_output_json(discovery, augmented_rmse)},
                       {"at_noise_floor", nlohmann::json::object()},
                       {"parameters", estimates_json(verdict ? verdict->result : discovery.base)}};
  for (std::size_t k = 0; k < augmented_at_noise.size(); ++k)
    json["augmented"]["at_noise_floor"][problem_of(discovery).outputs[k].channel] =
        static_cast<bool>(augmented_at_noise[k]);
  json["gap_shrink"] = verdict ? verdict->gap_shrink : 0.0;
  json["gap_closed"] = number_or_null(discovery.gap_closed);
  json["noise"] = per_output_json(discovery, discovery.noise);
  json["noise_floor"] = per_output_json(discovery, discovery.setup.floor);
  json["noise_floor_source"] = nlohmann::json::object();
  json["at_noise_floor"] = nlohmann::json::object();
  json["residual_white"] = nlohmann::json::object();
  json["structured_rms"] = nlohmann::json::object();
  for (std::size_t k = 0; k < discovery.setup.floor.size(); ++k) {
    const std::string& channel = problem_of(discovery).outputs[k].channel;
    json["noise_floor_source"][channel] =
        discovery.setup.floor_given[k] ? "given (--noise)" : "estimated from the data";
    json["at_noise_floor"][channel] = static_cast<bool>(discovery.at_noise[k]);
    json["residual_white"][channel] = residual_white(discovery, k);
    json["structured_rms"][channel] =
        structured_rms(discovery.base.validation.rmse[k], discovery.setup.floor[k]);
  }
  json["spikes_replaced"] = nlohmann::json::object();
  for (std::size_t k = 0; k < discovery.setup.cleaned.size(); ++k)
    json["spikes_replaced"][problem_of(discovery).outputs[k].channel] = discovery.setup.cleaned[k];
  json["diagnostics"] = diagnostics_json(discovery.diagnostics);
  const auto& request = discovery.setup.request;
  json["settings"] = {{"validate_from", request.validate_from},
                      {"bic_threshold", request.bic_threshold},
                      {"min_gap_shrink", request.min_gap_shrink},
                      {"min_signature", request.min_signature},
                      {"alias_correlation", request.alias_correlation},
                      {"despike_all", request.despike_all},
                      {"floor_margin", request.floor_margin},
                      {"min_gap_closed", request.min_gap_closed},
                      {"max_order", request.max_order},
                      {"starts", request.starts},
                      {"seed", request.seed}};
  json["simulations"] = discovery.simulations;
  json["seconds"] = discovery.seconds;
  return json.dump(2) + "\n";
}

std::string discovery_summary(const Discovery& discovery) {
  std::ostringstream out;
  const auto& outputs = problem_of(discovery).outputs;
  out << "discover " << discovery.setup.request.model_file << " on "
      << discovery.setup.request.data_file << ": " << discovery.simulations << " simulations in "
      << text(discovery.seconds) << " s\n";
  out << "  baseline validation RMSE:";
  for (std::size_t k = 0; k < outputs.size(); ++k)
    out << " " << outputs[k].channel << " " << text(discovery.base.validation.rmse[k], 4) << " "
        << outputs[k].unit;
  out << "\n  noise floor:";
  for (std::size_t k = 0; k < outputs.size(); ++k)
    out << " " << outputs[k].channel << " " << text(discovery.setup.floor[k], 4) << " "
        << outputs[k].unit << (discovery.setup.floor_given[k] ? " (given)" : " (from the data)")
        << (discovery.at_noise[k] ? ", base at it" : ", base above it")
        << (residual_white(discovery, k) ? "" : " (residual not white)");
  // The effect column fits the longest label ("temperature_dependent_stiffness [2]").
  const auto label = [](const CandidateOutcome& candidate) {
    return candidate.name + " [" + std::to_string(candidate.order) + "]";
  };
  std::size_t width = 34;
  for (const auto& candidate : discovery.candidates)
    width = std::max(width, label(candidate).size() + 2);
  for (const auto& skipped : discovery.skipped) width = std::max(width, skipped.name.size() + 2);
  const int column = static_cast<int>(width);
  out << "\n  " << std::left << std::setw(column) << "effect" << std::setw(12) << "delta BIC"
      << std::setw(12) << "gap shrink" << std::setw(13) << "signature z"
      << "significant\n";
  for (const auto& candidate : discovery.candidates) {
    out << "  " << std::setw(column) << label(candidate);
    if (candidate.status != "fitted") {
      out << candidate.status << ": " << candidate.reason << "\n";
      continue;
    }
    out << std::setw(12) << text(candidate.delta_bic, 4) << std::setw(12)
        << text(candidate.gap_shrink, 3) << std::setw(13) << text(candidate.signature_z, 3)
        << (candidate.significant ? "yes" : "no")
        << (candidate.superseded ? " (another member of its family does better)" : "") << "\n";
  }
  for (const auto& skipped : discovery.skipped)
    out << "  " << std::setw(column) << skipped.name << "skipped: " << skipped.reason << "\n";
  out << "verdict: " << discovery.verdict;
  if (const auto* verdict = verdict_of(discovery))
    out << " (" << verdict->member << "; validation gap shrinks by "
        << text(100 * verdict->gap_shrink, 3) << " %, " << text(100 * discovery.gap_closed, 3)
        << " % of the gap above the noise floor closed)"
        << (verdict->aliases.empty() ? "" : "." + aliases_text(*verdict));
  else if (discovery.kind == VerdictKind::none)
    out << " (the base model fits to the noise floor)";
  else
    out << " (the base model misses by more than the noise and no candidate explains it)";
  out << "\n";
  if (const std::string missed = missed_with_effect(discovery); !missed.empty())
    out << "  with it the model still misses the noise floor (" << missed
        << "): another effect may be missing; discover again with augmented.yaml as --model (what "
           "--max-effects does)\n";
  return out.str();
}

std::string discovery_report(const Discovery& discovery) {
  std::ostringstream out;
  const auto& request = discovery.setup.request;
  const auto& problem = problem_of(discovery);
  out << "# tcpmsim discover: " << discovery.verdict << "\n\n";
  out << "Base model `" << request.model_file << "` against `" << request.data_file
      << "`: identification [" << text(problem.identification.from, 6) << " s, "
      << text(problem.identification.to, 6) << " s], validation ["
      << text(problem.validation.from, 6) << " s, " << text(problem.validation.to, 6) << " s].\n\n";
  out << "## The base fit\n\n| parameter | estimate | standard error | unit |\n|---|---|---|---|\n";
  for (const auto& estimate : discovery.base.estimates)
    out << "| " << estimate.path << " | " << text(estimate.value, 6) << " | "
        << text(estimate.standard_error, 3) << (estimate.identifiable ? "" : " (not identified)")
        << " | " << estimate.unit << " |\n";
  if (!discovery.base.identifiability.empty()) {
    out << "\n**Warning**: the data leave parameters of the base model poorly identified, so an "
           "effect may trade against them and its estimates with theirs; fix or remove them "
           "(--parameters) before reading much into the numbers:\n\n";
    for (const auto& problem : discovery.base.identifiability) out << "- " << problem << "\n";
  }
  out << "\n## Where the base model disagrees (validation residual)\n\n";
  for (std::size_t k = 0; k < discovery.diagnostics.outputs.size(); ++k) {
    const auto& output = discovery.diagnostics.outputs[k];
    out << "- **" << output.channel << "**: RMSE " << text(discovery.base.validation.rmse[k], 4)
        << " " << problem.outputs[k].unit << " (identification "
        << text(discovery.base.identification.rmse[k], 4)
        << "); Ljung-Box p = " << text(output.whiteness.p_value, 2)
        << (residual_white(discovery, k) ? " (white)" : " (not white)")
        << "; drift t = " << text(output.drift.t_statistic, 2) << "; power share by band";
    for (std::size_t b = 0; b < discovery.diagnostics.bands.size(); ++b)
      out << (b ? ", " : " ") << text(discovery.diagnostics.bands[b].first, 2) << "-"
          << text(discovery.diagnostics.bands[b].second, 2) << " Hz "
          << text(100 * output.band_share[b], 2) << " %";
    out << "; correlation with";
    bool first = true;
    for (const auto& [feature, value] : output.features) {
      out << (first ? " " : ", ") << feature << " " << text(value, 2);
      first = false;
    }
    out << " (white: |corr| < " << text(discovery.diagnostics.bound, 2) << ")";
    if (!output.loop.frequency.empty())
      out << "; loop area against deflection ~ f^" << text(output.loop.exponent, 2);
    out << ".\n";
  }
  out << "\n## Candidates\n\n| effect | form | delta BIC | gap shrink | signature z (corr) | "
         "significant | evidence in the base residual |\n|---|---|---|---|---|---|---|\n";
  for (const auto& candidate : discovery.candidates) {
    if (candidate.status != "fitted") {
      out << "| " << candidate.name << " | " << candidate.member
          << " | failed: " << candidate.reason << " | | | | |\n";
      continue;
    }
    out << "| " << candidate.name << " | " << candidate.member
        << (candidate.superseded ? " (not its family's best)" : "")
        << (candidate.retried ? " (refitted from zero size)" : "")
        << (candidate.drawn_kept ? " (refitted from a drawn start)" : "") << " | "
        << text(candidate.delta_bic, 4) << " | " << text(100 * candidate.gap_shrink, 3) << " % | "
        << text(candidate.signature_z, 3) << " (" << text(candidate.signature_match, 2) << ") | "
        << (candidate.significant ? "yes" : "no") << " | " << candidate.signature_evidence
        << " |\n";
  }
  for (const auto& skipped : discovery.skipped)
    out << "| " << skipped.name << " | | skipped: " << skipped.reason << " | | | | |\n";
  out << "\nA candidate is significant when it lowers the BIC by more than "
      << text(request.bic_threshold) << " on the identification window, shrinks the validation "
      << "RMSE by more than " << text(100 * request.min_gap_shrink) << " %, and the change it "
      << "makes to the outputs explains the base model's validation residual, which no fit has "
      << "seen (its signature: the matched-filter z = sum(r d) / |d| in noise units, standard "
      << "normal for a residual of noise alone, at least " << text(request.min_signature)
      << "), and it closes at least " << text(100 * request.min_gap_closed)
      << " % of the gap above the noise floor: of the outputs the base model misses by more "
         "than the noise (beyond "
      << text(100 * request.floor_margin)
      << " % of the floor), or, where it misses none, of the outputs' gap combined (nothing is "
         "asked where the base model is at or below its floors combined). Every candidate starts "
         "from the base fit with its effect at zero size, where it is "
         "the base model, so its fit can only end at or below the base model's cost; one that "
         "ends above is fitted again from there and otherwise reported as failed. Within a "
         "family (one Dahl element or a Prandtl-Ishlinskii operator, one relaxation branch or "
         "two) the member with the lowest BIC competes. The base model was refitted from the "
         "best candidate's base parameters ("
      << discovery.base_rounds
      << (discovery.base_rounds > 1 ? " candidate rounds: re-tuning improved it" : " round")
      << "), so re-tuning them is not counted as an effect.\n\n"
         "## Verdict\n\n";
  if (const auto* verdict = verdict_of(discovery)) {
    out << "**" << verdict->name << "**: " << verdict->description << ". Validation RMSE";
    for (std::size_t k = 0; k < problem.outputs.size(); ++k)
      out << " " << problem.outputs[k].channel << " " << text(discovery.base.validation.rmse[k], 4)
          << " -> " << text(verdict->validation_rmse[k], 4) << " " << problem.outputs[k].unit;
    out << " (gap shrink " << text(100 * verdict->gap_shrink, 3) << " %). Form: " << verdict->member
        << ". " << verdict->signature << ": " << verdict->signature_evidence << ".";
    out << " The effect closes " << text(100 * discovery.gap_closed, 3)
        << " % of the gap above the noise floor." << aliases_text(*verdict) << "\n";
    if (const std::string missed = missed_with_effect(discovery); missed.empty())
      out << "\nWith it the model fits every output to within " << text(100 * request.floor_margin)
          << " % of its noise floor.\n";
    else
      out << "\nWith it the model still misses by more than the noise (validation RMSE " << missed
          << " its floor): another effect may be missing. Run discover again with "
             "`augmented.yaml` as `--model` (`--max-effects` does so): the named effect stays "
             "attached with its fitted "
             "values, and every candidate joins it (to refit the named effect too, list its "
             "parameters with the base laws' in `--parameters`).\n";
  } else if (discovery.kind == VerdictKind::none) {
    out << "**none**: the base model fits to the noise floor (every output's validation RMSE is "
           "within "
        << text(100 * request.floor_margin) << " % of its floor), and no candidate improves it "
        << "significantly.\n";
    write_sliver_at_floor(out, discovery);
    write_structured_rest(out, discovery);
  } else {
    out << "**unexplained**: the base model misses by more than the noise, and no candidate of "
           "the catalogue explains it. Do not read this as a complete model.\n";
  }
  out << "\nNoise floor (validation RMSE of the base model against it):";
  for (std::size_t k = 0; k < problem.outputs.size(); ++k)
    out << " " << problem.outputs[k].channel << " " << text(discovery.setup.floor[k], 4) << " "
        << problem.outputs[k].unit << " ("
        << (discovery.setup.floor_given[k] ? "given" : "estimated from the data") << "; "
        << text(discovery.base.validation.rmse[k] / discovery.setup.floor[k], 3) << " times)";
  out << ".\n";
  if (discovery.kind == VerdictKind::unexplained) {
    out << "\nWhat the base residual follows, strongest first (multiples of what white noise "
           "reaches):\n\n";
    for (std::size_t k = 0; k < problem.outputs.size(); ++k) {
      if (discovery.at_noise[k]) continue;
      const auto ranked = ranked_signatures(discovery.diagnostics, k);
      out << "- **" << problem.outputs[k].channel << "**: ";
      for (std::size_t i = 0; i < std::min<std::size_t>(ranked.size(), 5); ++i)
        out << (i ? "; " : "") << ranked[i].what << " (" << text(ranked[i].strength, 2) << "x)";
      out << ".\n";
    }
    const auto* best = discovery.candidates.empty() ? nullptr : &discovery.candidates.front();
    const double closed = best && best->status == "fitted" && !std::isnan(best->missed_gap_closed)
                              ? best->missed_gap_closed
                              : 0.0;
    out << "\nThe best candidate" << (best ? " (" + best->name + ", " + best->member + ")" : "")
        << " closes " << text(100 * closed, 3)
        << " % of the gap above the noise floor of the outputs the base model misses; "
        << text(100 * (1 - closed), 3) << " % remains.\n";
  }
  return out.str();
}

std::vector<std::string> write_discovery(const std::string& directory, const Discovery& discovery,
                                         const Provenance& provenance) {
  std::filesystem::create_directories(directory);
  const auto in = [&](const char* name) {
    return (std::filesystem::path(directory) / name).string();
  };
  std::vector<std::string> written;
  const auto put = [&](const char* name, const std::string& content) {
    const std::string path = in(name);
    std::ofstream file(path);
    file << content;
    if (!file) throw std::runtime_error("cannot write " + path);
    written.push_back(path);
  };
  const std::string& data = discovery.setup.request.data_file;
  put("baseline.yaml",
      fitted_scenario_yaml(spec_for_yaml(discovery.setup.base, data), discovery.base));
  const CandidateOutcome* verdict = verdict_of(discovery);
  // Without a verdict's effect there is no augmented model: one an earlier discover left in the
  // directory must not stand beside this one's files.
  std::error_code ignored;
  if (!verdict) std::filesystem::remove(in("augmented.yaml"), ignored);
  if (verdict)
    put("augmented.yaml",
        fitted_scenario_yaml(spec_for_yaml(verdict->spec, data), verdict->result));

  const FitProblem& problem = problem_of(discovery);
  const TimeWindow whole{problem.identification.from, problem.validation.to};
  std::vector<double> base_values, augmented_values;
  for (const auto& estimate : discovery.base.estimates) base_values.push_back(estimate.value);
  const auto measured = measured_outputs(problem, whole);
  const auto baseline = simulate_outputs(problem, base_values, whole);
  auto augmented = baseline;
  if (verdict) {
    for (const auto& estimate : verdict->result.estimates)
      augmented_values.push_back(estimate.value);
    augmented = simulate_outputs(verdict->spec.problem, augmented_values, whole);
  }
  const auto [first, last] = samples_in(*problem.data, whole);
  const auto& time = problem.data->time();
  const std::string traces = in("traces.h5");
  Hdf5Writer writer(traces);
  writer.provenance(provenance);
  writer.write("/time",
               std::vector<double>(time.begin() + static_cast<long>(first),
                                   time.begin() + static_cast<long>(last)),
               "s");
  for (std::size_t k = 0; k < problem.outputs.size(); ++k) {
    const auto& output = problem.outputs[k];
    std::vector<double> before(measured[k].size()), after(measured[k].size());
    for (std::size_t i = 0; i < measured[k].size(); ++i) {
      before[i] = measured[k][i] - baseline[k][i];
      after[i] = measured[k][i] - augmented[k][i];
    }
    writer.write("/measured/" + output.channel, measured[k], output.unit);
    writer.write("/baseline/" + output.channel, baseline[k], output.unit);
    writer.write("/augmented/" + output.channel, augmented[k], output.unit);
    writer.write("/residual/baseline/" + output.channel, before, output.unit);
    writer.write("/residual/augmented/" + output.channel, after, output.unit);
    const auto& diagnosed = discovery.diagnostics.outputs[k];
    const std::string group = "/diagnostics/" + output.channel;
    writer.write(group + "/loop_frequency", diagnosed.loop.frequency, "Hz");
    writer.write(group + "/loop_quadrature", diagnosed.loop.quadrature, output.unit + "/m");
    for (const auto& [input, cross] : diagnosed.inputs)
      writer.write(group + "/cross_correlation/" + input, cross.values, "1");
    std::vector<std::string> names;
    std::vector<double> values;
    for (const auto& [feature, value] : diagnosed.features) {
      names.push_back(feature);
      values.push_back(value);
    }
    writer.write_strings(group + "/feature_names", names);
    writer.write(group + "/feature_correlation", values, "1");
  }
  writer.write("/identification_window",
               std::vector<double>{problem.identification.from, problem.identification.to}, "s");
  writer.write("/validation_window",
               std::vector<double>{problem.validation.from, problem.validation.to}, "s");
  writer.attribute("/", "verdict", discovery.verdict);
  writer.attribute("/", "augmented_effect", verdict ? verdict->name : "none");
  writer.commit();
  written.push_back(traces);
  put("discovery.json", discovery_json(discovery));
  put("report.md", discovery_report(discovery));
  return written;
}

}  // namespace tcpmsim::fit
