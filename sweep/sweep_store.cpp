#include "sweep/sweep_store.h"

#include <H5Cpp.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "sim/config/config_node.h"
#include "sim/io/delimited_file.h"
#include "sim/io/hdf5_files.h"
#include "sim/io/hdf5_writer.h"

namespace tcpmsim::sweep {
namespace {

constexpr const char* kIdentityFile = "sweep.identity";
constexpr const char* kOwnerLock = "sweep.lock";
constexpr const char* kWritersLock = "writers.lock";

std::string run_name(std::size_t id, std::size_t runs) {
  const std::size_t width = std::to_string(runs > 0 ? runs - 1 : 0).size();
  std::string text = std::to_string(id);
  return std::string(width - std::min(width, text.size()), '0') + text;
}

// A run's part, as merge reads it back.
struct Part {
  std::vector<double> values;
  std::vector<double> metrics;
  bool succeeded = false;
  std::string message;
  double wall_seconds = 0.0;
};

// Every dataset under `group`, with its path relative to `prefix`.
void copy_traces(const H5::H5File& file, const std::string& group, const std::string& prefix,
                 Hdf5Writer& writer) {
  H5::Group node = file.openGroup(group);
  for (hsize_t k = 0; k < node.getNumObjs(); ++k) {
    const std::string name = node.getObjnameByIdx(k);
    const std::string path = group + "/" + name;
    if (node.getObjTypeByIdx(k) == H5G_GROUP) {
      copy_traces(file, path, prefix + "/" + name, writer);
    } else {
      const H5::DataSet set = file.openDataSet(path);
      writer.write(prefix + "/" + name, read_doubles(file, path), units_of(set));
    }
  }
}

// A run's traces into /runs/<name>/ of the output; a run that failed before any trace has
// none.
void copy_run_traces(const std::string& path, const std::string& name, Hdf5Writer& output) {
  const std::lock_guard lock(hdf5_mutex());
  try {
    const H5::H5File file(path, H5F_ACC_RDONLY);
    if (file.nameExists("/traces")) copy_traces(file, "/traces", "/runs/" + name, output);
  } catch (const H5::Exception& error) {
    throw std::runtime_error("cannot read " + path + ": " + error.getDetailMsg());
  }
}

// A part whose contents are not what this sweep's runs write (damaged, or edited).
[[noreturn]] void refuse_part(const std::string& path, const std::string& problem) {
  throw DataFileError({path, 0, 0, {}}, problem + ": not a run of this sweep as it writes them " +
                                            "(damaged?); remove it and --resume to run it again");
}

// `columns` and `metrics`: how many values and metrics this sweep's runs write.
Part read_part(const std::string& path, std::size_t columns, std::size_t metrics) {
  const std::lock_guard lock(hdf5_mutex());
  Part part;
  try {
    const H5::H5File file(path, H5F_ACC_RDONLY);
    part.values = read_doubles(file, "/values");
    part.metrics = read_doubles(file, "/metrics");
    const auto succeeded = read_doubles(file, "/succeeded");
    const auto message = read_texts(file, "/message");  // a scalar: one text
    const auto wall_seconds = read_doubles(file, "/wall_seconds");
    if (succeeded.size() != 1 || message.size() != 1 || wall_seconds.size() != 1)
      refuse_part(path, "its status, message or wall time is not one value");
    part.succeeded = succeeded[0] != 0.0;
    part.message = message[0];
    part.wall_seconds = wall_seconds[0];
  } catch (const H5::Exception& error) {
    refuse_part(path, "cannot read it: " + error.getDetailMsg());
  }
  if (part.values.size() != columns || part.metrics.size() != metrics)
    refuse_part(path, "it holds " + std::to_string(part.values.size()) + " values and " +
                          std::to_string(part.metrics.size()) + " metrics where the sweep has " +
                          std::to_string(columns) + " and " + std::to_string(metrics));
  return part;
}

void write_text_file(const std::string& path, const std::string& text) {
  {
    std::ofstream out(partial_path(path), std::ios::binary);
    out << text;
    if (!out.flush()) throw std::runtime_error("cannot write " + path);
  }
  std::filesystem::rename(partial_path(path), path);
}

}  // namespace

std::string sweep_identity(const SweepSpec& spec) {
  std::ostringstream text;
  text << "# sweep of " << spec.runs.size() << " runs\n" << spec.resolved_yaml;
  for (const auto& scenario : spec.scenarios)
    text << "\n# scenario " << scenario.name << "\n" << scenario.scenario->resolved_yaml;
  return text.str();
}

SweepStore::SweepStore(const SweepSpec& spec, std::string output, Access access)
    : spec_(spec), output_(std::move(output)), parts_(output_ + ".parts") {
  namespace fs = std::filesystem;
  if (access == Access::join) {
    if (visible()) writer_lock_ = FileLock(parts_ + "/" + kWritersLock, FileLock::Mode::shared);
    return;
  }
  prepare_output_file(output_);  // a directory or a device is refused before any run, as by run
  const std::string identity_file = parts_ + "/" + kIdentityFile;
  const std::string identity = sweep_identity(spec);
  const bool interrupted = fs::exists(parts_);
  create_parent_directories(identity_file);
  lock_out_other_sweeps();  // before anything of the parts or the output is touched
  // The file is written when the sweep ends; until then its runs are in the parts directory,
  // and an empty partial file left by a killed sweep would only look like a record.
  std::filesystem::remove(partial_path(output_));
  if (interrupted) {
    if (access != Access::resume)
      throw std::runtime_error("the runs of an interrupted sweep are in " + parts_ +
                               ": --resume to finish it, or remove them to start afresh");
    if (!fs::exists(identity_file) || read_text_file(identity_file) != identity)
      throw std::runtime_error(parts_ + " holds runs of another sweep (its file or scenarios " +
                               "changed): remove them to start afresh");
    // A run killed while its part was being written left only the temporary file.
    for (const auto& entry : fs::directory_iterator(parts_)) {
      if (entry.path().extension() == ".partial") fs::remove(entry.path());
    }
    return;
  }
  write_text_file(identity_file, identity);
}

void SweepStore::lock_out_other_sweeps() {
  owner_lock_ = FileLock(parts_ + "/" + kOwnerLock, FileLock::Mode::exclusive);
  if (!owner_lock_.taken())
    throw std::runtime_error("another sweep is writing into " + parts_ +
                             " now: let it end, or stop it, before this one starts");
  const std::string writers = parts_ + "/" + kWritersLock;
  if (!FileLock(writers, FileLock::Mode::exclusive).taken())
    throw std::runtime_error("processes of an earlier sweep still write into " + parts_ +
                             " (the ranks of a launcher that was killed before them?): stop "
                             "them before this sweep starts");
  writer_lock_ = FileLock(writers, FileLock::Mode::shared);
}

bool SweepStore::visible() const {
  return std::filesystem::exists(parts_ + "/" + kIdentityFile);
}

std::string SweepStore::part_path(std::size_t id) const {
  return parts_ + "/run_" + run_name(id, spec_.runs.size()) + ".h5";
}

std::vector<std::size_t> SweepStore::pending() const {
  std::vector<std::size_t> ids;
  for (std::size_t id = 0; id < spec_.runs.size(); ++id) {
    if (!std::filesystem::exists(part_path(id))) ids.push_back(id);
  }
  return ids;
}

void SweepStore::write(const RunResult& result) const {
  Hdf5Writer part(part_path(result.id));
  part.write("/values", result.values, "");
  part.write("/metrics", result.metrics, "");
  part.write("/succeeded", std::vector<double>{result.succeeded ? 1.0 : 0.0}, "1");
  part.write_strings("/message", {result.message});
  part.write("/wall_seconds", std::vector<double>{result.wall_seconds}, "s");
  for (const auto& trace : result.traces) {
    const std::string group = "/traces/" + trace.scenario;
    part.write(group + "/time", trace.time, "s");
    for (std::size_t c = 0; c < trace.channels.size(); ++c)
      part.write(group + "/" + trace.channels[c], trace.values[c], trace.units[c]);
  }
  part.commit();
}

std::size_t SweepStore::merge(const std::string& invocation) const {
  const std::size_t runs = spec_.runs.size();
  const auto columns = value_columns(spec_);
  std::vector<std::vector<double>> values(columns.size()), metrics(spec_.metrics.size());
  std::vector<long long> ids;
  std::vector<std::string> status, messages;
  std::vector<double> wall;
  std::size_t failed = 0;
  Hdf5Writer output(output_);
  for (std::size_t id = 0; id < runs; ++id) {
    const Part part = read_part(part_path(id), columns.size(), metrics.size());
    ids.push_back(static_cast<long long>(id));
    for (std::size_t c = 0; c < columns.size(); ++c) values[c].push_back(part.values.at(c));
    for (std::size_t m = 0; m < metrics.size(); ++m) metrics[m].push_back(part.metrics.at(m));
    status.push_back(part.succeeded ? "ok" : "failed");
    failed += part.succeeded ? 0 : 1;
    messages.push_back(part.message);
    wall.push_back(part.wall_seconds);
    if (spec_.traces != TraceStorage::none)
      copy_run_traces(part_path(id), run_name(id, runs), output);
  }
  output.write_integers("/summary/id", ids);
  for (std::size_t c = 0; c < columns.size(); ++c) {
    const Axis* axis = c < spec_.axes.size() ? &spec_.axes[c] : nullptr;
    if (axis != nullptr && axis->structural)
      output.write_strings("/summary/" + summary_column(columns[c].first), axis->texts);
    else
      output.write("/summary/" + summary_column(columns[c].first), values[c], columns[c].second);
  }
  for (std::size_t m = 0; m < metrics.size(); ++m)
    output.write("/summary/" + spec_.metrics[m].name, metrics[m], spec_.metrics[m].unit);
  output.write_strings("/summary/status", status);
  output.write_strings("/summary/message", messages);
  output.write("/timing/wall_seconds", wall, "s");
  output.provenance({invocation, {{spec_.file, spec_.resolved_yaml, std::to_string(spec_.seed)}}});
  output.attribute("/", "sweep", spec_.name);
  output.attribute("/", "sweep_file", spec_.file);
  output.attribute("/", "sweep_config", spec_.resolved_yaml);
  output.attribute("/", "runs", std::to_string(runs));
  output.attribute("/", "failed_runs", std::to_string(failed));
  output.commit();
  // The runs first, the identity last: a merge killed here leaves parts a resume still takes.
  for (std::size_t id = 0; id < runs; ++id) std::filesystem::remove(part_path(id));
  finish_writing();
  owner_lock_.release();
  std::filesystem::remove_all(parts_);
  return failed;
}

void SweepStore::finish_writing() const {
  writer_lock_.release();
}

}  // namespace tcpmsim::sweep
