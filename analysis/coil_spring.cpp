#include "analysis/coil_spring.h"

#include <algorithm>
#include <filesystem>

namespace tcpmsim::analysis {

namespace {
// The spring's `data` directory, or the spring file's own.
std::string data_directory_of(const ConfigNode& node) {
  if (const auto data = node.find("data")) return file_named_by(*data);
  const std::string file = node.location().file;
  const std::string directory = std::filesystem::path(file).parent_path().string();
  return directory.empty() ? "." : directory;
}
}  // namespace

CoilSpring CoilSpring::from_config(const ConfigNode& root) {
  root.declare({"coil_spring"});
  const ConfigNode node = root.at("coil_spring");
  node.declare({"name", "wire_diameter", "outer_diameter", "body_length", "turns", "sequences",
                "calibration", "data"});
  CoilSpring spring;
  spring.source = node.location().file;
  spring.name = node.text("name");
  spring.wire_diameter = node.quantity("wire_diameter", "m", ValueCheck::positive());
  spring.outer_diameter = node.quantity("outer_diameter", "m", ValueCheck::positive());
  if (!(spring.outer_diameter > 2.0 * spring.wire_diameter)) {
    node.at("outer_diameter")
        .fail("expected an outer diameter above twice the wire diameter, got '" +
              node.at("outer_diameter").as_text() + "'");
  }
  spring.body_length = node.quantity("body_length", "m", ValueCheck::positive());
  if (!(spring.body_length > 2.0 * spring.wire_diameter)) {
    node.at("body_length")
        .fail("expected a body length of more than two wire diameters, got '" +
              node.at("body_length").as_text() + "'");
  }
  // Close wound at rest: one wire diameter per turn over the coil length (physics.md).
  spring.turns = node.number_or("turns", spring.coil_length() / spring.wire_diameter,
                                ValueCheck::at_least(1.0));
  const ConfigNode sequences = node.at("sequences");
  if (!sequences.is_sequence() || sequences.elements().empty()) {
    sequences.fail("expected a list of measurement sequences (data file stems such as S1_01)");
  }
  for (const ConfigNode& element : sequences.elements()) {
    const std::string name = element.as_text();
    if (name.empty() || name.find('/') != std::string::npos) {
      element.fail("expected a data file stem such as 'S1_01', got '" + name + "'");
    }
    spring.sequences.push_back({name, element.location()});
  }
  spring.calibration = spring.sequences.front().name;
  if (const auto calibration = node.find("calibration")) {
    spring.calibration = calibration->as_text();
    const bool listed =
        std::any_of(spring.sequences.begin(), spring.sequences.end(),
                    [&](const Sequence& s) { return s.name == spring.calibration; });
    if (!listed) {
      calibration->fail("expected one of the spring's sequences, got '" + spring.calibration + "'");
    }
  }
  spring.data_directory = data_directory_of(node);
  root.reject_unknown_keys();
  return spring;
}

CoilSpring load_coil_spring(const std::string& file, std::shared_ptr<const UnitSystem> units) {
  return CoilSpring::from_config(ConfigNode::load_file(file, {}, std::move(units)));
}

}  // namespace tcpmsim::analysis
