#include "identification/measured_roles.h"

#include <yaml-cpp/yaml.h>

#include <functional>

namespace tcpmsim::fit {

namespace {

bool is_data_signal(const YAML::Node& node) {
  return node.IsMap() && node["type"] && node["type"].IsScalar() &&
         node["type"].as<std::string>() == "data" && node["channel"] && node["channel"].IsScalar();
}

// Calls `visit(key, signal)` for every data signal of the YAML tree, in document order; `key`
// is the map key it stands under ("" in a sequence).
void for_each_data_signal(const YAML::Node& root,
                          const std::function<void(const std::string&, const YAML::Node&)>& visit) {
  std::function<void(const std::string&, const YAML::Node&)> walk = [&](const std::string& key,
                                                                        const YAML::Node& node) {
    if (is_data_signal(node)) visit(key, node);
    if (node.IsMap()) {
      for (const auto& entry : node)
        walk(entry.first.IsScalar() ? entry.first.as<std::string>() : std::string(), entry.second);
    } else if (node.IsSequence()) {
      for (const auto& entry : node) walk("", entry);
    }
  };
  walk("", root);
}

}  // namespace

std::vector<std::string> replayed_channels(const std::string& resolved_yaml) {
  std::vector<std::string> channels;
  for_each_data_signal(YAML::Load(resolved_yaml), [&](const std::string&, const YAML::Node& node) {
    channels.push_back(node["channel"].as<std::string>());
  });
  return channels;
}

std::string channel_carrying(const Scenario& model, const MeasuredData& data,
                             const std::vector<FitOutput>& outputs, const std::string& quantity) {
  std::string replayed;
  for_each_data_signal(YAML::Load(model.resolved_yaml),
                       [&](const std::string& key, const YAML::Node& node) {
                         const auto channel = node["channel"].as<std::string>();
                         if (replayed.empty() && key == quantity && data.find(channel))
                           replayed = channel;
                       });
  if (!replayed.empty()) return replayed;
  const std::string suffix = "." + quantity;
  for (const auto& output : outputs)
    if (output.output.ends_with(suffix) && data.find(output.channel)) return output.channel;
  return quantity;
}

MeasuredRoles measured_roles(const Scenario& model, const MeasuredData& data,
                             const std::vector<FitOutput>& outputs) {
  return {channel_carrying(model, data, outputs, "power"),
          channel_carrying(model, data, outputs, "deflection")};
}

}  // namespace tcpmsim::fit
