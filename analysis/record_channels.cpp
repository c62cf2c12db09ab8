#include "analysis/record_channels.h"

#include <H5Cpp.h>

#include <algorithm>
#include <filesystem>
#include <stdexcept>

#include "sim/config/config_error.h"
#include "sim/io/hdf5_files.h"
#include "sim/io/input_descriptions.h"
#include "sim/io/record_layout.h"

namespace tcpmsim {
namespace {

const std::vector<double>* array_of(const SignalDescription& description, const std::string& name) {
  for (const auto& [key, values] : description.arrays)
    if (key == name) return &values;
  return nullptr;
}

// "drive.power" -> "drive/power"; a member set's ("b/drive.power") has no 1-D channel.
std::string channel_of_input(const std::string& input_path) {
  std::string channel = input_path;
  const auto dot = channel.rfind('.');
  if (dot != std::string::npos) channel[dot] = '/';
  return channel;
}

void add_input(RecordChannels& record, const std::string& input_path,
               const SignalDescription& description, bool member_set) {
  const std::string channel = channel_of_input(input_path);
  const auto found = record.channels.find(channel);
  if (member_set || found == record.channels.end() || found->second.columns != 1) return;
  const double end = record.time.empty() ? 0.0 : record.time.back();
  record.inputs[channel] = multisine_stretches(description, 0.0, end);
}

// Every dataset with a `units` attribute whose first dimension is the record's time.
void read_channels(const H5::Group& group, const std::string& prefix, RecordChannels& record) {
  for (hsize_t k = 0; k < group.getNumObjs(); ++k) {
    const std::string name = group.getObjnameByIdx(k);
    const std::string path = prefix.empty() ? name : prefix + "/" + name;
    if (path == "inputs" || path == "time") continue;
    if (group.childObjType(name) == H5O_TYPE_GROUP) {
      read_channels(group.openGroup(name), path, record);
      continue;
    }
    const H5::DataSet set = group.openDataSet(name);
    const H5::DataSpace space = set.getSpace();
    const int rank = space.getSimpleExtentNdims();
    if (rank < 1 || rank > 2) continue;
    hsize_t dimensions[2] = {0, 1};
    space.getSimpleExtentDims(dimensions);
    if (dimensions[0] != record.time.size()) continue;  // a member set's fixed facts
    record.channels[path] = {read_doubles(group, name), units_of(set),
                             static_cast<std::size_t>(rank == 2 ? dimensions[1] : 1)};
  }
}

}  // namespace

std::vector<MultisineStretch> multisine_stretches(const SignalDescription& description,
                                                  double begin, double end) {
  if (description.type == "multisine") {
    const auto* frequencies = array_of(description, "frequencies");
    if (frequencies == nullptr) return {};
    return {{begin, end, *frequencies}};
  }
  std::vector<MultisineStretch> stretches;
  const auto* starts = array_of(description, "starts");
  if (description.type != "sequence" || starts == nullptr ||
      starts->size() != description.parts.size())
    return stretches;
  for (std::size_t k = 0; k < starts->size(); ++k) {
    const double from = begin + (*starts)[k];
    const double to = k + 1 < starts->size() ? begin + (*starts)[k + 1] : end;
    if (from >= end) break;
    for (auto& stretch : multisine_stretches(description.parts[k].description, from, to))
      stretches.push_back(std::move(stretch));
  }
  return stretches;
}

const RecordChannels::Channel& RecordChannels::channel(const std::string& name) const {
  const auto found = channels.find(name);
  if (found != channels.end()) return found->second;
  std::string names;
  for (const auto& [known, _] : channels) names += (names.empty() ? "" : ", ") + known;
  throw std::invalid_argument(source + " has no channel '" + name + "'; it has " + names);
}

namespace {

// A file analyze cannot read at all: a data-file error located at the file.
[[noreturn]] void unreadable(const std::string& path, const std::string& problem) {
  throw ConfigError({path, 0, 0, {}}, "", problem);
}

}  // namespace

RecordChannels read_record_channels(const std::string& path) {
  const std::lock_guard lock(hdf5_mutex());
  RecordChannels record;
  record.source = path;
  if (!std::filesystem::is_regular_file(path)) unreadable(path, "no such file");
  try {
    H5::Exception::dontPrint();
    const H5::H5File file(path, H5F_ACC_RDONLY);
    if (!file.attrExists("tcpmsim_version"))
      unreadable(path, "not a tcpmsim record: it has no 'tcpmsim_version' attribute");
    if (!file.nameExists("time"))  // a tcpmsim file of another kind (an analysis, a summary)
      throw std::runtime_error(path + " is not a tcpmsim record (it has no /time)");
    record.time = read_doubles(file, "time");
    record.scenario = read_text_attribute(file, "scenario");
    record.config_file = read_text_attribute(file, "config_file");
    record.config = read_text_attribute(file, "config");
    if (file.attrExists("seed")) {
      const H5::Attribute attribute = file.openAttribute("seed");
      require_single_value(attribute);
      std::uint64_t seed = 0;
      attribute.read(H5::PredType::NATIVE_UINT64, &seed);
      record.seed = std::to_string(seed);
    }
    read_channels(file, "", record);
    for (const auto& input : read_record_inputs(file))
      add_input(record, input.path, input.description, !input.members.empty());
  } catch (const H5::Exception&) {
    unreadable(path, "cannot read it as HDF5: damaged, truncated, or not an HDF5 file");
  }
  return record;
}

RecordChannels memory_record_channels(const Scenario& scenario, const MemoryRun& run) {
  RecordChannels record;
  record.source = "the run of '" + scenario.settings.name + "'";
  record.scenario = scenario.settings.name;
  record.config_file = scenario.source;
  record.config = scenario.resolved_yaml;
  record.seed = std::to_string(scenario.settings.seed);
  record.time = run.time;
  for (std::size_t k = 0; k < run.series.size(); ++k) {
    const auto& series = run.series[k];
    record.channels[series.group + "/" + series.name] = {run.values[k], series.unit,
                                                         series.signal_indices.size()};
  }
  Context context = scenario.make_context();
  scenario.system->prepare(context);  // the signals as the run had them
  for (const auto& entry : input_layout(*scenario.system))
    add_input(record, entry.path, context.signal(entry.slots.front()).describe(),
              !entry.members.empty());
  return record;
}

}  // namespace tcpmsim
