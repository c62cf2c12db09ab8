#pragma once

#include <memory>
#include <span>
#include <string>
#include <vector>

namespace tcpmsim {

// What made a file: the command line (or the Python call) and the configuration files it read,
// each with its resolved text (a scenario's YAML as read, overrides and defaults included) and
// seed. Written as root attributes: command_line, config_files, configs and seeds (text
// arrays); every file also carries tcpmsim_version and git_commit.
struct Provenance {
  struct Config {
    std::string file;
    std::string resolved;  // YAML
    std::string seed;      // decimal; empty when the file has none
  };
  std::string command_line;
  std::vector<Config> configs;
};

// Writes analysis results to one HDF5 file as flat datasets (1-D or 2-D doubles, or strings),
// each number with a `units` attribute, in groups created on demand ("/S1_01/models/maxwell/
// inductance"). Like the simulation record, the file is written as "<path>.partial" and renamed
// by commit(); destroying an uncommitted writer removes the partial file. HDF5 failures are
// reported as std::runtime_error naming the file.
class Hdf5Writer {
 public:
  explicit Hdf5Writer(std::string path);
  ~Hdf5Writer();
  Hdf5Writer(const Hdf5Writer&) = delete;
  Hdf5Writer& operator=(const Hdf5Writer&) = delete;

  void write(const std::string& dataset, std::span<const double> values, const std::string& units);
  // A rows x columns matrix given row by row.
  void write_matrix(const std::string& dataset, std::span<const double> row_major, std::size_t rows,
                    std::size_t columns, const std::string& units);
  void write_scalar(const std::string& dataset, double value, const std::string& units);
  void write_strings(const std::string& dataset, const std::vector<std::string>& values);
  // 1-D 64-bit integers (counts, identifiers), with units "1".
  void write_integers(const std::string& dataset, std::span<const long long> values);
  // A text attribute on an existing object ("/" for the file).
  void attribute(const std::string& object, const std::string& name, const std::string& value);

  // The provenance's attributes on the root.
  void provenance(const Provenance& provenance);

  // Writes tcpmsim_version and git_commit on the root, closes the file and renames it to its
  // final path.
  void commit();

 private:
  struct File;
  std::string path_;
  std::unique_ptr<File> file_;
  bool committed_ = false;
};

}  // namespace tcpmsim
