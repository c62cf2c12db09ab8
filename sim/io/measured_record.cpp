// A tcpmsim record read as a measurement, so that a simulated run stands in for an experiment.
#include <algorithm>
#include <cmath>
#include <mutex>

#include "sim/io/hdf5_files.h"
#include "sim/io/measured_data.h"

namespace tcpmsim {

namespace {

[[noreturn]] void fail(const std::string& path, const std::string& problem) {
  throw DataFileError({path, 0, 0, {}}, problem);
}

// Every 1-D dataset of `samples` values under `group` (but /inputs, which describes signals),
// named by its path with '.'.
void collect(const H5::H5File& file, const std::string& group, const std::string& prefix,
             std::size_t samples, std::vector<MeasuredChannel>& channels) {
  const H5::Group node = file.openGroup(group.empty() ? "/" : group);
  for (hsize_t k = 0; k < node.getNumObjs(); ++k) {
    const std::string name = node.getObjnameByIdx(k);
    const std::string path = group + "/" + name;
    const std::string channel = prefix.empty() ? name : prefix + "." + name;
    if (node.getObjTypeByIdx(k) == H5G_GROUP) {
      if (path != "/inputs") collect(file, path, channel, samples, channels);
      continue;
    }
    if (path == "/time" || node.getObjTypeByIdx(k) != H5G_DATASET) continue;
    const H5::DataSet set = file.openDataSet(path);
    const H5::DataSpace space = set.getSpace();
    if (space.getSimpleExtentNdims() != 1 ||
        static_cast<std::size_t>(space.getSimpleExtentNpoints()) != samples ||
        set.getTypeClass() != H5T_FLOAT) {
      continue;  // a member set's 2-D series, a table of the scenario: not a channel
    }
    const std::string units = units_of(set);
    channels.push_back({channel, units, units, read_doubles(file, path)});
  }
}

// A single-muscle record read as the bench would have measured it: each quantity's plain name
// ("force") is the instrument's channel: the drive's, else the load's (the testing machine and
// its load cell), else the muscle's.
void add_bench_names(std::vector<MeasuredChannel>& channels) {
  const std::size_t recorded = channels.size();
  for (const auto& quantity : measured_quantities()) {
    for (const char* instrument : {"drive.", "load.", "muscle."}) {
      const std::string path = instrument + std::string(quantity.name);
      const auto found = std::find_if(channels.begin(), channels.begin() + recorded,
                                      [&](const auto& channel) { return channel.name == path; });
      if (found == channels.begin() + recorded) continue;
      MeasuredChannel named = *found;
      named.name = quantity.name;
      channels.push_back(std::move(named));
      break;
    }
  }
}

}  // namespace

MeasuredData read_measured_record(const std::string& path) {
  const std::lock_guard lock(hdf5_mutex());
  std::vector<double> time;
  std::vector<MeasuredChannel> channels;
  try {
    H5::Exception::dontPrint();
    const H5::H5File file(path, H5F_ACC_RDONLY);
    if (!file.nameExists("/time")) {
      fail(path, "not a tcpmsim record: it has no /time dataset");
    }
    if (units_of(file.openDataSet("/time")) != "s") {
      fail(path, "/time is not in s; expected a tcpmsim record");
    }
    time = read_doubles(file, "/time");
    collect(file, "", "", time.size(), channels);
    add_bench_names(channels);
  } catch (const H5::Exception& error) {
    fail(path, "cannot read the HDF5 record: " + error.getDetailMsg());
  }
  if (time.empty()) fail(path, "the record holds no samples");
  for (std::size_t k = 1; k < time.size(); ++k) {
    if (!(time[k] > time[k - 1])) {
      fail(path, "/time[" + std::to_string(k) + "] does not increase; a record's times must");
    }
  }
  for (const auto& channel : channels) {
    const auto bad = std::find_if(channel.values.begin(), channel.values.end(),
                                  [](double value) { return !std::isfinite(value); });
    if (bad != channel.values.end()) {
      fail(path, channel.name + "[" + std::to_string(bad - channel.values.begin()) +
                     "] is not a finite number");
    }
  }
  return MeasuredData(path, std::move(time), std::move(channels));
}

}  // namespace tcpmsim
