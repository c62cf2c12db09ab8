#include "identification/discovery_runs.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>

#include "identification/discovery_report.h"
#include "identification/joint_refit.h"
#include "identification/json_numbers.h"
#include "identification/output_error_fit.h"
#include "sim/config/config_error.h"
#include "sim/value_check.h"

namespace tcpmsim::fit {

namespace {

std::string in_directory(const std::string& directory, const char* name) {
  return (std::filesystem::path(directory) / name).string();
}

EffectRun run_of(const Discovery& discovery, int number, const std::string& directory) {
  EffectRun run;
  run.number = number;
  run.directory = directory;
  run.model = discovery.setup.request.model_file;
  run.verdict = discovery.verdict;
  run.named = discovery.kind == VerdictKind::effect;
  run.gap_closed = discovery.gap_closed;
  run.still_missed = missed_with_effect(discovery);
  run.floor_margin = discovery.setup.request.floor_margin;
  if (run.named) {
    // The named candidate frees the base model's parameters, then its effect's.
    const auto& freed = discovery.candidates.front().spec.problem.parameters;
    run.effect_parameters.assign(freed.begin() + static_cast<long>(discovery.base.estimates.size()),
                                 freed.end());
  }
  return run;
}

// "hysteresis and slow_relaxation"; a family named in two runs once, with its count:
// "hysteresis x2".
std::string joined_names(const std::vector<std::string>& names) {
  std::vector<std::pair<std::string, int>> counted;
  for (const auto& name : names) {
    auto seen = std::find_if(counted.begin(), counted.end(),
                             [&](const auto& entry) { return entry.first == name; });
    if (seen == counted.end())
      counted.emplace_back(name, 1);
    else
      ++seen->second;
  }
  std::string text;
  for (std::size_t k = 0; k < counted.size(); ++k) {
    text += (k == 0 ? "" : k + 1 == counted.size() ? " and " : ", ") + counted[k].first;
    if (counted[k].second > 1) text += " x" + std::to_string(counted[k].second);
  }
  return text;
}

std::string run_line(const EffectRun& run) {
  std::ostringstream out;
  out << "  " << run.number << "  " << run.verdict << ": ";
  if (run.named && std::isnan(run.gap_closed))
    out << "named with the model before it at the noise floor";
  else if (run.named)
    out << "closes " << number_text(100 * run.gap_closed, 3)
        << " % of the gap above the noise floor" << (run.number > 1 ? " that remained" : "");
  else if (run.verdict == "none")
    out << "refitted, the model fits to the noise floor";
  else if (run.verdict == "unexplained")
    out << "the model misses by more than the noise and no candidate explains it";
  else
    out << run.failure;
  out << " (" << run.directory << ")\n";
  return out.str();
}

}  // namespace

FinalModel final_model(const std::vector<EffectRun>& runs, const JointRefit* joint) {
  FinalModel model;
  for (const auto& run : runs)
    if (run.named) model.effects.push_back(run.verdict);
  if (model.effects.empty()) return model;
  if (joint && joint->failure.empty() && joint->better) {
    model.path = in_directory(joint->directory, "fitted.yaml");
    model.at_floor = joint->at_floor;
    model.still_missed = joint->still_missed;
    return model;
  }
  const EffectRun& last = runs.back();
  if (last.named) {
    model.path = in_directory(last.directory, "augmented.yaml");
    model.still_missed = last.still_missed;
    model.at_floor = last.still_missed.empty();
  } else if (last.verdict == "failed") {
    const EffectRun& before = runs[runs.size() - 2];
    model.path = in_directory(before.directory, "augmented.yaml");
    model.still_missed = before.still_missed;
  } else {
    model.path = in_directory(last.directory, "baseline.yaml");
    model.at_floor = last.verdict == "none";
  }
  return model;
}

std::string effect_run_directory(const std::string& out, int number) {
  if (number <= 1) return out;
  return (std::filesystem::path(out) / ("effect" + std::to_string(number))).string();
}

std::vector<std::string> earlier_effect_runs(const std::string& out) {
  std::vector<std::string> found;
  const std::filesystem::path directory(out);
  std::error_code error;
  // Only an earlier discover with --max-effects wrote effects.json: without it, directories
  // named effect2, ... are someone else's.
  if (!std::filesystem::is_regular_file(directory / "effects.json", error)) return found;
  found.push_back((directory / "effects.json").string());
  for (int number = 2;; ++number) {
    const std::filesystem::path run = effect_run_directory(out, number);
    if (!std::filesystem::is_directory(run, error)) break;
    // A run's directory holds its discovery.json, or nothing when its base fit failed.
    const bool a_run = std::filesystem::exists(run / "discovery.json", error) ||
                       std::filesystem::is_empty(run, error);
    if (error || !a_run) break;
    found.push_back(run.string());
  }
  // The joint refit's directory holds its fit.json, or nothing when the refit failed.
  const std::filesystem::path joint = directory / "joint";
  if (std::filesystem::is_directory(joint, error) &&
      (std::filesystem::exists(joint / "fit.json", error) ||
       std::filesystem::is_empty(joint, error)))
    found.push_back(joint.string());
  return found;
}

void check_outside_effect_runs(const DiscoverRequest& request, const std::string& out,
                               int max_effects) {
  auto replaced = earlier_effect_runs(out);
  for (int number = 2; number <= max_effects; ++number)
    replaced.push_back(effect_run_directory(out, number));
  if (max_effects > 1) replaced.push_back(in_directory(out, "joint"));
  for (const auto* name : {"augmented.yaml", "baseline.yaml", "traces.h5"})
    replaced.push_back(in_directory(out, name));
  // "" when `file` is neither `target` nor inside it, else ".", or its path inside it.
  const auto relative_to = [](const std::string& file, const std::string& target) {
    std::error_code error;
    const auto path = std::filesystem::weakly_canonical(file, error).lexically_normal();
    const auto base = std::filesystem::weakly_canonical(target, error).lexically_normal();
    const auto relative = path.lexically_relative(base);
    return relative.empty() || *relative.begin() == ".." ? std::string() : relative.string();
  };
  for (const auto& [option, file] :
       {std::pair{"--model", request.model_file}, std::pair{"--data", request.data_file}}) {
    for (const auto& target : replaced) {
      const std::string relative = relative_to(file, target);
      if (relative.empty()) continue;
      throw UsageError(std::string(option) + " " + file +
                       (relative == "." ? " is a file" : " lies in " + target + ", a directory") +
                       " this discover writes over (--out " + out +
                       "); copy it elsewhere or give another --out");
    }
  }
}

std::vector<std::string> remove_earlier_effect_runs(const std::string& out) {
  std::vector<std::string> removed;
  for (const auto& path : earlier_effect_runs(out)) {
    std::error_code error;
    std::filesystem::remove_all(path, error);
    if (error) throw std::runtime_error("cannot remove " + path + ": " + error.message());
    removed.push_back(path);
  }
  return removed;
}

bool another_effect_due(const Discovery& discovery) {
  return discovery.kind == VerdictKind::effect && !missed_with_effect(discovery).empty();
}

DiscoverRequest next_effect_request(DiscoverRequest request, const std::string& augmented_model) {
  request.model_file = augmented_model;
  request.overrides.clear();
  return request;
}

std::vector<EffectRun> discover_effects(const DiscoverSetup& first, int max_effects,
                                        const std::string& out, const EffectRunWriter& write,
                                        const EffectRunAnnouncer& announce) {
  check_outside_effect_runs(first.request, out, max_effects);
  remove_earlier_effect_runs(out);
  std::vector<EffectRun> runs;
  DiscoverRequest next = first.request;
  for (int number = 1; number <= max_effects; ++number) {
    const std::string directory = effect_run_directory(out, number);
    if (number == 1) {
      const Discovery discovery = discover(first);
      write(discovery, directory);
      runs.push_back(run_of(discovery, number, directory));
      if (!another_effect_due(discovery)) break;
      continue;
    }
    next = next_effect_request(next, in_directory(runs.back().directory, "augmented.yaml"));
    if (announce) announce(number, directory, next.model_file);
    // A later run that cannot go on (its base fit fails, its model does not load from where
    // the run before wrote it, its files cannot be written) ends the sequence: the runs before
    // stand, and effects.json says why.
    try {
      std::filesystem::create_directories(directory);
      const Discovery discovery = discover(setup_discovery(next, first.units));
      write(discovery, directory);
      runs.push_back(run_of(discovery, number, directory));
      if (!another_effect_due(discovery)) break;
    } catch (const std::exception& error) {
      EffectRun failed;
      failed.number = number;
      failed.directory = directory;
      failed.model = next.model_file;
      failed.verdict = "failed";
      failed.failure = dynamic_cast<const FitFailure*>(&error)
                           ? std::string("the base model's fit failed: ") + error.what()
                           : std::string(error.what());
      failed.floor_margin = next.floor_margin;
      runs.push_back(failed);
      break;
    }
  }
  return runs;
}

std::string effect_runs_summary(const std::vector<EffectRun>& runs, int max_effects,
                                const JointRefit* joint) {
  std::ostringstream out;
  out << "\neffects sought one a run (--max-effects " << max_effects << "):\n";
  for (const auto& run : runs) out << run_line(run);
  if (joint) out << joint_refit_summary(*joint);
  const FinalModel model = final_model(runs, joint);
  if (model.effects.empty()) {
    out << "no effect named\n";
    return out.str();
  }
  out << "the model with " << joined_names(model.effects) << ": " << model.path << "; ";
  if (model.at_floor)
    out << "it fits every output to within " << number_text(100 * runs.back().floor_margin, 3)
        << " % of its noise floor\n";
  else if (!model.still_missed.empty())
    out << "it still misses the noise floor (" << model.still_missed << ")"
        << (runs.back().named && int(runs.size()) == max_effects
                ? ": --max-effects reached, raise it to look for another"
                : "")
        << "\n";
  else
    out << "it still misses the noise floor, and no candidate explains the rest\n";
  return out.str();
}

std::string effect_runs_json(const std::vector<EffectRun>& runs, int max_effects,
                             const JointRefit* joint) {
  nlohmann::json json;
  json["max_effects"] = max_effects;
  json["runs"] = nlohmann::json::array();
  for (const auto& run : runs) {
    json["runs"].push_back({{"run", run.number},
                            {"directory", run.directory},
                            {"model", run.model},
                            {"verdict", run.verdict},
                            {"gap_closed", number_or_null(run.named ? run.gap_closed : NAN)},
                            {"still_missed", run.still_missed},
                            {"failure", run.failure}});
  }
  const FinalModel model = final_model(runs, joint);
  json["effects"] = model.effects;
  json["model"] = model.path.empty() ? nlohmann::json() : nlohmann::json(model.path);
  json["at_noise_floor"] = model.path.empty() ? nlohmann::json() : nlohmann::json(model.at_floor);
  json["joint"] = joint ? joint_refit_json(*joint) : nlohmann::json();
  return json.dump(2) + "\n";
}

}  // namespace tcpmsim::fit
