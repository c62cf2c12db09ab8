#pragma once

#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "sim/config/units.h"
#include "sim/io/delimited_file.h"

namespace tcpmsim {

// A quantity a measurement file may hold: its column name and the SI unit it is converted to.
struct MeasuredQuantity {
  std::string_view name;                                     // "force"
  std::string_view si_unit;                                  // "N"
  std::string_view what;                                     // "a force"
  std::string_view examples;                                 // "N, mN"
  double lowest = -std::numeric_limits<double>::infinity();  // the physical range, SI
  double highest = std::numeric_limits<double>::infinity();
};

// Every quantity a data file's header may name: time, power, duty, current, deflection, force,
// temperature, ambient_temperature, inductance, inductance_measure, decay_time, resistance.
const std::vector<MeasuredQuantity>& measured_quantities();
// The quantity of a channel name, its instance prefix ignored ("left.force" is a force); null
// if the name is none of them.
const MeasuredQuantity* measured_quantity_of(std::string_view channel);

// One measured channel, in SI.
struct MeasuredChannel {
  std::string name;       // "force", "left.force"; in a record, its path ("load.force")
  std::string unit;       // the SI unit of `values`
  std::string file_unit;  // the unit the file wrote
  std::vector<double> values;
};

// A measurement: strictly increasing sample times [s] and channels of as many samples, all in
// SI. Read from a CSV file (read_measured_csv) or a tcpmsim record (read_measured_record).
class MeasuredData {
 public:
  MeasuredData(std::string file, std::vector<double> time, std::vector<MeasuredChannel> channels);

  const std::string& file() const { return file_; }
  const std::vector<double>& time() const { return time_; }
  const std::vector<MeasuredChannel>& channels() const { return channels_; }
  // The channel of that name, or null.
  const MeasuredChannel* find(std::string_view name) const;
  // Why `name` cannot be had: "<file> has no channel 'forse' (did you mean 'force'?); its
  // channels: time, power, force". For the reader that asked to place in its own error.
  std::string missing_channel(std::string_view name) const;

 private:
  std::string file_;
  std::vector<double> time_;
  std::vector<MeasuredChannel> channels_;
};

// A data time for a message: "12.5 s", to 12 digits.
std::string seconds_text(double seconds);

// A comma-separated file whose first line (after '#' comment lines) names each column as
// `name[unit]`: "time[s],power[W],deflection[mm],force[N],decay_time[us]". Units are converted
// through `units` (udunits, as the scenarios are). Every bad file gets one DataFileError with
// file:line:column: an empty file, a header without time or with an unknown or repeated
// channel, a unit that is unknown or not of its quantity, a ragged row, a value that is not a
// finite number, a time that does not increase.
MeasuredData read_measured_csv(const std::string& path, const UnitSystem& units);
MeasuredData parse_measured_csv(const std::string& text, const std::string& name,
                                const UnitSystem& units);

// A tcpmsim record standing in for a measurement: /time and every 1-D dataset of as many
// samples, named by its path with '.' ("load.force", "muscle.temperature"). Each quantity's
// plain name is also the bench's instrument for it: the drive's channel, else the load's (the
// testing machine and load cell), else the muscle's ("force" is "load.force").
MeasuredData read_measured_record(const std::string& path);

// A record if the file is HDF5, else CSV.
MeasuredData read_measured_data(const std::string& path, const UnitSystem& units);

}  // namespace tcpmsim
