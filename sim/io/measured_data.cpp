#include "sim/io/measured_data.h"

#include <filesystem>
#include <mutex>
#include <sstream>

#include "sim/config/config_node.h"
#include "sim/io/hdf5_files.h"

namespace tcpmsim {

const std::vector<MeasuredQuantity>& measured_quantities() {
  constexpr double any = std::numeric_limits<double>::infinity();
  static const std::vector<MeasuredQuantity> quantities = {
      {"time", "s", "a time", "s, ms", -any, any},
      {"power", "W", "a power", "W, mW", 0.0, any},  // Joule heating takes, never gives
      {"duty", "1", "a duty cycle (dimensionless)", "1, %", 0.0, 1.0},
      {"current", "A", "a current", "A, mA", -any, any},
      {"deflection", "m", "a length", "m, mm, um", -any, any},
      {"force", "N", "a force", "N, mN", -any, any},
      {"temperature", "K", "a temperature", "K, degC", 0.0, any},
      {"ambient_temperature", "K", "a temperature", "K, degC", 0.0, any},
      {"inductance", "H", "an inductance", "H, mH, uH", 0.0, any},
      {"inductance_measure", "1", "the dimensionless inductance measure L*", "1", -any, any},
      {"decay_time", "s", "a time", "s, us", 0.0, any},
      {"resistance", "ohm", "a resistance", "ohm, mohm", 0.0, any},
  };
  return quantities;
}

const MeasuredQuantity* measured_quantity_of(std::string_view channel) {
  const auto dot = channel.rfind('.');
  const std::string_view base = dot == std::string_view::npos ? channel : channel.substr(dot + 1);
  for (const auto& quantity : measured_quantities()) {
    if (quantity.name == base) return &quantity;
  }
  return nullptr;
}

MeasuredData::MeasuredData(std::string file, std::vector<double> time,
                           std::vector<MeasuredChannel> channels)
    : file_(std::move(file)), time_(std::move(time)), channels_(std::move(channels)) {}

const MeasuredChannel* MeasuredData::find(std::string_view name) const {
  for (const auto& channel : channels_) {
    if (channel.name == name) return &channel;
  }
  return nullptr;
}

std::string MeasuredData::missing_channel(std::string_view name) const {
  std::vector<std::string> names;
  for (const auto& channel : channels_) names.push_back(channel.name);
  std::string problem = file_ + " has no channel '" + std::string(name) + "'";
  const std::string suggestion = closest_match(name, names);
  if (!suggestion.empty()) problem += " (did you mean '" + suggestion + "'?)";
  problem += "; its channels: time";
  for (const auto& channel : names) problem += ", " + channel;
  return problem;
}

std::string seconds_text(double seconds) {
  std::ostringstream text;
  text.precision(12);
  text << seconds << " s";
  return text.str();
}

namespace {

// Whether HDF5 itself takes the file for one (it also finds a signature after a user block).
bool is_hdf5(const std::string& path) {
  if (!std::filesystem::is_regular_file(path)) return false;
  const std::lock_guard lock(hdf5_mutex());
  H5::Exception::dontPrint();
  try {
    return H5::H5File::isHdf5(path);
  } catch (const H5::Exception&) {
    return false;
  }
}

}  // namespace

MeasuredData read_measured_data(const std::string& path, const UnitSystem& units) {
  return is_hdf5(path) ? read_measured_record(path) : read_measured_csv(path, units);
}

}  // namespace tcpmsim
