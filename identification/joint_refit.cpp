#include "identification/joint_refit.h"

#include <algorithm>
#include <filesystem>
#include <sstream>

#include "identification/discovery_report.h"
#include "identification/json_numbers.h"
#include "identification/output_error_fit.h"
#include "sim/value_check.h"

namespace tcpmsim::fit {

namespace {

// Per output: "force 1.31 -> 1.12 mN" of two RMSE vectors in SI units, shown in mN for newtons.
std::string changes(const FitSpec& spec, const std::vector<double>& before,
                    const std::vector<double>& after) {
  std::string text;
  for (std::size_t k = 0; k < spec.problem.outputs.size(); ++k) {
    const auto& output = spec.problem.outputs[k];
    const double scale = output.unit == "N" ? 1e3 : 1.0;
    const std::string unit = output.unit == "N" ? "mN" : output.unit;
    text += (k == 0 ? "" : ", ") + output.channel + " " + number_text(before[k] * scale, 4) +
            " -> " + number_text(after[k] * scale, 4) + (unit == "1" ? "" : " " + unit);
  }
  return text;
}

}  // namespace

bool joint_refit_due(const std::vector<EffectRun>& runs) {
  return std::count_if(runs.begin(), runs.end(), [](const EffectRun& run) { return run.named; }) >=
         2;
}

JointRefit refit_jointly(const DiscoverRequest& first, const std::vector<EffectRun>& runs,
                         const std::string& out, std::shared_ptr<const UnitSystem> units) {
  JointRefit joint;
  joint.directory = (std::filesystem::path(out) / "joint").string();
  const FinalModel ended = final_model(runs);
  joint.start_model = ended.path;
  try {
    const DiscoverSetup setup = setup_discovery(next_effect_request(first, ended.path), units);
    joint.floor = setup.floor;
    joint.spec = setup.base;
    auto& problem = joint.spec.problem;
    for (const auto& run : runs) {
      for (const auto& parameter : run.effect_parameters) {
        const bool freed =
            std::any_of(problem.parameters.begin(), problem.parameters.end(),
                        [&](const FitParameter& other) { return other.path == parameter.path; });
        if (freed) continue;
        problem.parameters.push_back(parameter);
        ++joint.effect_parameters;
      }
    }
    // Weighted as discover weights its fits: by each output's identification RMSE, here the
    // start model's (it already fits nearly to the noise where the runs ended at the floor).
    const std::vector<double> noise = initial_noise(problem);
    for (std::size_t k = 0; k < noise.size(); ++k) problem.outputs[k].noise = noise[k];
    // From the model's values alone (no drawn starts): every named effect sits where its run
    // fitted it, and the fit can only go down from there. A value its run left on a bound can lie
    // a rounding step beyond it after the trip through the unit interval, outside the box the
    // optimiser searches: it starts on the bound.
    auto& settings = joint.spec.settings;
    settings.starts = 0;
    settings.refine = 1;
    settings.start.clear();
    const Context context = problem.model->make_context();
    for (const auto& parameter : problem.parameters)
      settings.start.push_back(
          std::clamp(context.parameter(parameter.path), parameter.lower, parameter.upper));
    joint.result = fit_model(problem, settings);
    std::vector<double> start;
    for (const auto& estimate : joint.result.estimates) start.push_back(estimate.initial);
    joint.start_identification_rmse = score_window(problem, start, problem.identification).rmse;
    joint.start_validation_rmse = score_window(problem, start, problem.validation).rmse;
    joint.still_missed = outputs_above_floor(problem.outputs, joint.result.validation.rmse,
                                             joint.floor, first.floor_margin);
    joint.at_floor = joint.still_missed.empty();
    // No larger an error on the validation window, over the outputs combined; and where the
    // runs' model fits every output to its floor, so must the refit.
    joint.better = combined_rmse(joint.result.validation.rmse, joint.floor) <=
                       combined_rmse(joint.start_validation_rmse, joint.floor) &&
                   (joint.at_floor || !ended.at_floor);
  } catch (const std::exception& error) {
    joint.failure = error.what();
  }
  return joint;
}

std::string joint_refit_summary(const JointRefit& joint) {
  std::ostringstream out;
  if (!joint.failure.empty()) {
    out << "refitted together: failed (" << joint.failure << "); the runs' model stands\n";
    return out.str();
  }
  const FitResult& result = joint.result;
  out << "refitted together (the base laws' " << result.estimates.size() - joint.effect_parameters
      << " parameters and the named effects' " << joint.effect_parameters << ", from "
      << joint.start_model << "):\n"
      << "  identification error "
      << changes(joint.spec, joint.start_identification_rmse, result.identification.rmse)
      << "\n  validation error "
      << changes(joint.spec, joint.start_validation_rmse, result.validation.rmse) << "\n  "
      << joint.directory << "/fitted.yaml (" << joint.directory
      << "/fit.json: every estimate with its standard error); "
      << (joint.better ? "the better model on the validation window"
                       : "worse on the validation window than the runs' model, which stands")
      << (result.converged ? "" : "; the fit stopped at its iteration limit") << "\n";
  return out.str();
}

nlohmann::json joint_refit_json(const JointRefit& joint) {
  const bool made = joint.failure.empty();
  nlohmann::json json = {
      {"directory", joint.directory},
      {"model", made ? nlohmann::json(joint.directory + "/fitted.yaml") : nlohmann::json()},
      {"start_model", joint.start_model},
      {"failure", joint.failure}};
  if (!made) return json;
  const auto& outputs = joint.spec.problem.outputs;
  const auto pairs = [&](const std::vector<double>& before, const std::vector<double>& after) {
    nlohmann::json per_output = nlohmann::json::object();
    for (std::size_t k = 0; k < outputs.size(); ++k)
      per_output[outputs[k].channel] = {number_or_null(before[k]), number_or_null(after[k])};
    return per_output;
  };
  json["parameters"] = joint.result.estimates.size();
  json["effect_parameters"] = joint.effect_parameters;
  json["identification_rmse"] =
      pairs(joint.start_identification_rmse, joint.result.identification.rmse);
  json["validation_rmse"] = pairs(joint.start_validation_rmse, joint.result.validation.rmse);
  json["better"] = joint.better;
  json["at_noise_floor"] = joint.at_floor;
  json["converged"] = joint.result.converged;
  return json;
}

}  // namespace tcpmsim::fit
