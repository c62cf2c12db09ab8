#include "identification/fit_report.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <sstream>

#include "identification/json_numbers.h"
#include "kinds/standard_kinds.h"
#include "sim/config/config_node.h"
#include "sim/io/hdf5_writer.h"

namespace tcpmsim::fit {

namespace {

nlohmann::json window_json(const FitSpec& spec, const WindowScore& score) {
  nlohmann::json window = nlohmann::json::object();
  for (std::size_t k = 0; k < score.rmse.size(); ++k) {
    window[spec.problem.outputs[k].channel] = {{"rmse", number_or_null(score.rmse[k])},
                                               {"nrmse", number_or_null(score.nrmse[k])},
                                               {"r2", number_or_null(score.r2[k])}};
  }
  return window;
}

std::string window_lines(const FitSpec& spec, const char* name, const TimeWindow& window,
                         const WindowScore& score) {
  std::ostringstream out;
  for (std::size_t k = 0; k < score.rmse.size(); ++k) {
    const auto& output = spec.problem.outputs[k];
    out << "  " << std::left << std::setw(15) << name << std::setw(13) << output.channel << "["
        << number_text(window.from, 6) << " s, " << number_text(window.to, 6) << " s]  RMSE "
        << number_text(score.rmse[k], 4) << " " << output.unit << ", NRMSE "
        << number_text(score.nrmse[k], 4) << ", R2 " << number_text(score.r2[k], 6) << "\n";
  }
  return out.str();
}

// The node at a parameter's scenario path ("muscles.left.mechanics.k1", "muscle.effects[0].tau").
YAML::Node node_at(YAML::Node node, const std::string& path) {
  std::size_t start = 0;
  while (start < path.size()) {
    const std::size_t end = path.find_first_of(".[", start);
    const std::string key = path.substr(start, end - start);
    if (!key.empty()) node.reset(node[key]);
    if (end == std::string::npos) break;
    if (path[end] == '[') {
      const std::size_t close = path.find(']', end);
      node.reset(node[std::stoul(path.substr(end + 1, close - end - 1))]);
      start = close + 1;
      if (start < path.size() && path[start] == '.') ++start;
    } else {
      start = end + 1;
    }
  }
  return node;
}

}  // namespace

std::string fit_summary(const FitSpec& spec, const FitResult& result) {
  std::ostringstream out;
  out << "fit of " << spec.model_file << " to " << spec.data_file << ": " << result.iterations
      << " iterations, " << result.simulations << " simulations; " << result.termination << "\n"
      << "  gradient: " << result.gradient << "\n";
  // The path column fits the longest path (an effect's parameters run to 40 characters).
  int path_width = 36;
  for (const auto& estimate : result.estimates)
    path_width = std::max(path_width, static_cast<int>(estimate.path.size()) + 2);
  out << "  " << std::left << std::setw(path_width) << "parameter" << std::setw(16) << "initial"
      << std::setw(16) << "estimate" << std::setw(14) << "std. error"
      << "unit\n";
  for (const auto& estimate : result.estimates) {
    out << "  " << std::setw(path_width) << estimate.path << std::setw(16)
        << number_text(estimate.initial, 6) << std::setw(16) << number_text(estimate.value, 6)
        << std::setw(14)
        << (estimate.identifiable ? number_text(estimate.standard_error, 3)
            : std::isfinite(estimate.standard_error)
                ? number_text(estimate.standard_error, 3) + " (poor)"
                : std::string("unidentified"))
        << estimate.unit << "\n";
  }
  for (const auto& problem : result.identifiability) out << "  not identified: " << problem << "\n";
  for (const auto& estimate : result.estimates) {
    if (estimate.at_bound.empty()) continue;
    out << "  at a bound: " << estimate.path << " ended on its " << estimate.at_bound << " bound, "
        << number_text(estimate.value, 6) << " " << estimate.unit
        << "; the optimum may lie beyond it (widen the bounds, or ask why the data push it "
           "there)\n";
  }
  if (!result.converged) {
    out << "  not converged: the fit stopped at its limit of " << spec.settings.max_iterations
        << " iterations before a tolerance was met; the estimate is the best found (raise "
           "max_iterations in the fit file)\n";
  }
  out << window_lines(spec, "identification", spec.problem.identification, result.identification);
  if (!result.validation.rmse.empty())
    out << window_lines(spec, "validation", spec.problem.validation, result.validation);
  return out.str();
}

std::string fit_json(const FitSpec& spec, const FitResult& result) {
  nlohmann::json json;
  json["model"] = spec.model_file;
  json["data"] = spec.data_file;
  json["parameters"] = nlohmann::json::array();
  for (const auto& estimate : result.estimates) {
    json["parameters"].push_back(
        {{"path", estimate.path},
         {"unit", estimate.unit},
         {"initial", estimate.initial},
         {"estimate", estimate.value},
         {"standard_error", number_or_null(estimate.standard_error)},
         {"identifiable", estimate.identifiable},
         {"at_bound", estimate.at_bound.empty() ? nlohmann::json(nullptr)
                                                : nlohmann::json(estimate.at_bound)}});
  }
  json["correlation"] = nlohmann::json::array();
  for (Eigen::Index i = 0; i < result.correlation.rows(); ++i) {
    nlohmann::json row = nlohmann::json::array();
    for (Eigen::Index j = 0; j < result.correlation.cols(); ++j)
      row.push_back(number_or_null(result.correlation(i, j)));
    json["correlation"].push_back(row);
  }
  json["rank"] = result.rank;
  json["identifiability"] = result.identifiability;
  json["identification"] = window_json(spec, result.identification);
  json["validation"] = window_json(spec, result.validation);
  json["cost"] = result.cost;
  json["residual_variance"] = number_or_null(result.residual_variance);
  json["iterations"] = result.iterations;
  json["simulations"] = result.simulations;
  json["termination"] = result.termination;
  json["converged"] = result.converged;
  json["max_iterations"] = spec.settings.max_iterations;
  json["gradient"] = result.gradient;
  return json.dump(2) + "\n";
}

std::string fitted_scenario_yaml(const FitSpec& spec, const FitResult& result) {
  YAML::Node root = YAML::Load(spec.problem.model->resolved_yaml);
  const auto sections = instance_sections(standard_kinds());
  for (const auto& estimate : result.estimates) {
    node_at(root, expand_instance_path(root, estimate.path, sections)) =
        number_text(estimate.value, 17) + " " + estimate.unit;
  }
  YAML::Emitter out;
  out << root;
  const std::string command = spec.file.empty() ? "tcpmsim discover" : "tcpmsim fit " + spec.file;
  return "# " + spec.model_file + " fitted to " + spec.data_file + " by " + command + "\n" +
         out.c_str() + "\n";
}

std::vector<std::string> write_fit_outputs(const std::string& directory, const FitSpec& spec,
                                           const FitResult& result, const Provenance& provenance) {
  std::filesystem::create_directories(directory);
  const auto in = [&](const char* name) {
    return (std::filesystem::path(directory) / name).string();
  };
  for (const auto& [name, content] :
       {std::pair{"fit.json", fit_json(spec, result)},
        std::pair{"fitted.yaml", fitted_scenario_yaml(spec, result)}}) {
    std::ofstream file(in(name));
    file << content;
    if (!file) throw std::runtime_error(std::string("cannot write ") + in(name));
  }

  const TimeWindow whole{spec.problem.identification.from,
                         std::max(spec.problem.identification.to, spec.problem.validation.to)};
  std::vector<double> initial, fitted;
  for (const auto& estimate : result.estimates) {
    initial.push_back(estimate.initial);
    fitted.push_back(estimate.value);
  }
  const auto measured = measured_outputs(spec.problem, whole);
  const auto before = simulate_outputs(spec.problem, initial, whole);
  const auto after = simulate_outputs(spec.problem, fitted, whole);
  const auto [first, last] = samples_in(*spec.problem.data, whole);
  const auto& time = spec.problem.data->time();
  Hdf5Writer writer(in("fit.h5"));
  writer.provenance(provenance);
  writer.write("/time",
               std::vector<double>(time.begin() + static_cast<long>(first),
                                   time.begin() + static_cast<long>(last)),
               "s");
  for (std::size_t k = 0; k < spec.problem.outputs.size(); ++k) {
    const auto& output = spec.problem.outputs[k];
    writer.write("/measured/" + output.channel, measured[k], output.unit);
    writer.write("/initial/" + output.channel, before[k], output.unit);
    writer.write("/fitted/" + output.channel, after[k], output.unit);
  }
  writer.write(
      "/identification_window",
      std::vector<double>{spec.problem.identification.from, spec.problem.identification.to}, "s");
  writer.write("/validation_window",
               std::vector<double>{spec.problem.validation.from, spec.problem.validation.to}, "s");
  writer.commit();
  return {in("fit.json"), in("fitted.yaml"), in("fit.h5")};
}

}  // namespace tcpmsim::fit
