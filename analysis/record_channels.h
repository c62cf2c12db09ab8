#pragma once

#include <map>
#include <string>
#include <vector>

#include "sim/memory_run.h"
#include "sim/scenario.h"
#include "sim/signal.h"

namespace tcpmsim {

// Where a prescribed signal is a multisine, and at which frequencies.
struct MultisineStretch {
  double begin = 0.0;  // [s]
  double end = 0.0;
  std::vector<double> frequencies;  // [Hz]
};

// The multisine stretches of a signal described by `description` over [begin, end): a
// multisine's own, a sequence's segments' (its `starts` relative to `begin`), none for any other
// kind.
std::vector<MultisineStretch> multisine_stretches(const SignalDescription& description,
                                                  double begin, double end);

// A record's samples by channel, with units, and its prescribed inputs as channel names with
// their multisine stretches: what `tcpmsim analyze` reads, from a file or from a run in memory.
struct RecordChannels {
  struct Channel {
    std::vector<double> values;  // time x columns, row-major
    std::string unit;
    std::size_t columns = 1;
  };
  std::string source;  // the file, or the scenario's name
  std::string scenario;
  std::string config_file, config, seed;  // the run's scenario file, resolved YAML and seed
  std::vector<double> time;
  std::map<std::string, Channel> channels;  // "muscle/force"
  // Each prescribed signal of one instance that the record also holds as a channel
  // ("drive.power" as "drive/power"), with its multisine stretches (empty: not a multisine).
  std::map<std::string, std::vector<MultisineStretch>> inputs;

  // Throws std::invalid_argument naming the channels there are when `name` is not one.
  const Channel& channel(const std::string& name) const;
};

// Reads an HDF5 record written by tcpmsim (run, sweep parts, Result.save). Throws
// std::runtime_error for a file that is not such a record.
RecordChannels read_record_channels(const std::string& path);
// The same from a run kept in memory.
RecordChannels memory_record_channels(const Scenario& scenario, const MemoryRun& run);

}  // namespace tcpmsim
