#include "fmu/fmu_resources.h"

#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <stdexcept>

#include "kinds/standard_kinds.h"

namespace tcpmsim::fmu {

std::string settings_yaml(const FmuSettings& settings) {
  YAML::Emitter out;
  out << YAML::BeginMap << YAML::Key << "model_identifier" << YAML::Value
      << settings.model_identifier << YAML::Key << "outputs" << YAML::Value << YAML::Flow
      << settings.outputs << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

FmuResources read_fmu_resources(const std::string& directory,
                                std::shared_ptr<const UnitSystem> units) {
  const std::filesystem::path root(directory);
  const auto settings_file = root / kSettingsResource;
  const auto scenario_file = root / kScenarioResource;
  for (const auto& file : {settings_file, scenario_file})
    if (!std::filesystem::is_regular_file(file))
      throw std::runtime_error("the FMU's resources have no " + file.string());
  FmuSettings settings;
  try {
    const YAML::Node node = YAML::LoadFile(settings_file.string());
    settings.model_identifier = node["model_identifier"].as<std::string>();
    if (node["outputs"]) settings.outputs = node["outputs"].as<std::vector<std::string>>();
  } catch (const YAML::Exception& error) {
    throw std::runtime_error(settings_file.string() + ": " + error.what());
  }
  return {settings, load_scenario(scenario_file.string(), {}, std::move(units))};
}

std::optional<std::string> path_of_uri(const std::string& uri) {
  std::string rest;
  if (uri.rfind("file://localhost/", 0) == 0) {
    rest = uri.substr(16);
  } else if (uri.rfind("file:///", 0) == 0) {
    rest = uri.substr(7);
  } else if (uri.rfind("file:/", 0) == 0) {
    rest = uri.substr(5);
  } else {
    return std::nullopt;
  }
  std::string path;
  for (std::size_t k = 0; k < rest.size(); ++k) {
    if (rest[k] == '%' && k + 2 < rest.size() &&
        std::isxdigit(static_cast<unsigned char>(rest[k + 1])) &&
        std::isxdigit(static_cast<unsigned char>(rest[k + 2]))) {
      path += static_cast<char>(std::stoi(rest.substr(k + 1, 2), nullptr, 16));
      k += 2;
    } else {
      path += rest[k];
    }
  }
  return path;
}

}  // namespace tcpmsim::fmu
