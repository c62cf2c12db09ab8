#include "sim/io/hdf5_recorder.h"

#include <H5Cpp.h>

#include <filesystem>
#include <map>

#include "sim/io/hdf5_files.h"
#include "sim/signal.h"
#include "tcpmsim/version.h"

namespace tcpmsim {

struct Hdf5Recorder::File {
  H5::H5File file;
  std::map<std::string, H5::Group> groups;
  std::vector<H5::DataSet> datasets;  // [0] is /time
};

namespace {

template <typename T>
void write_scalar(H5::H5Object& object, const std::string& name, const H5::PredType& type,
                  T value) {
  H5::Attribute attribute = object.createAttribute(name, type, H5::DataSpace(H5S_SCALAR));
  attribute.write(type, &value);
}

H5::DataSet create_series(H5::Group& parent, const std::string& name, const std::string& units,
                          std::size_t chunk) {
  const hsize_t initial = 0, unlimited = H5S_UNLIMITED, chunk_size = chunk;
  H5::DataSpace space(1, &initial, &unlimited);
  H5::DSetCreatPropList properties;
  properties.setChunk(1, &chunk_size);
  properties.setShuffle();
  properties.setDeflate(1);
  H5::DataSet dataset = parent.createDataSet(name, H5::PredType::NATIVE_DOUBLE, space, properties);
  write_text_attribute(dataset, "units", units);
  return dataset;
}

void write_array(H5::Group& parent, const std::string& name, const std::vector<double>& values) {
  const hsize_t size = values.size();
  H5::DataSet dataset =
      parent.createDataSet(name, H5::PredType::NATIVE_DOUBLE, H5::DataSpace(1, &size));
  if (!values.empty()) dataset.write(values.data(), H5::PredType::NATIVE_DOUBLE);
}

void write_description(H5::Group& group, const SignalDescription& description) {
  write_text_attribute(group, "type", description.type);
  for (const auto& [name, value] : description.parameters) {
    write_scalar(group, name, H5::PredType::NATIVE_DOUBLE, value);
  }
  for (const auto& [name, values] : description.arrays) write_array(group, name, values);
  for (const auto& [name, part] : description.parts) {
    H5::Group child = group.createGroup(name);
    write_description(child, part);
  }
}

void write_statistics(H5::H5Object& root, const SolverStatistics& statistics) {
  const auto& type = H5::PredType::NATIVE_INT64;
  write_scalar(root, "solver_steps", type, std::int64_t{statistics.steps});
  write_scalar(root, "solver_rhs_evaluations", type, std::int64_t{statistics.rhs_evaluations});
  write_scalar(root, "solver_rhs_evaluations_for_jacobian", type,
               std::int64_t{statistics.rhs_evaluations_for_jacobian});
  write_scalar(root, "solver_jacobian_evaluations", type,
               std::int64_t{statistics.jacobian_evaluations});
  write_scalar(root, "solver_linear_solver_setups", type,
               std::int64_t{statistics.linear_solver_setups});
  write_scalar(root, "solver_error_test_failures", type,
               std::int64_t{statistics.error_test_failures});
  write_scalar(root, "solver_nonlinear_iterations", type,
               std::int64_t{statistics.nonlinear_iterations});
  write_scalar(root, "solver_nonlinear_convergence_failures", type,
               std::int64_t{statistics.nonlinear_convergence_failures});
  write_scalar(root, "solver_segments", type, std::int64_t{statistics.segments});
  write_scalar(root, "solver_events", type, std::int64_t{statistics.events});
  write_scalar(root, "samples", type, std::int64_t{statistics.output_samples});
}

}  // namespace

std::string Hdf5Recorder::failed_path(const std::string& path) {
  std::filesystem::path failed(path);
  const std::string extension = failed.extension().string();
  failed.replace_extension(".failed" + (extension.empty() ? std::string(".h5") : extension));
  return failed.string();
}

Hdf5Recorder::Hdf5Recorder(std::string path, const System& system, const Context& context,
                           const RecordMetadata& metadata, std::size_t chunk_samples)
    : path_(std::move(path)), file_(std::make_unique<File>()), chunk_samples_(chunk_samples) {
  H5::Exception::dontPrint();
  create_parent_directories(path_);
  file_->file = H5::H5File(partial_path(path_), H5F_ACC_TRUNC);
  H5::Group root = file_->file.openGroup("/");
  write_text_attribute(root, "tcpmsim_version", kVersion);
  write_text_attribute(root, "git_commit", kGitCommit);
  write_text_attribute(root, "scenario", metadata.scenario_name);
  write_text_attribute(root, "config_file", metadata.config_file);
  write_text_attribute(root, "config", metadata.resolved_config);
  write_scalar(root, "seed", H5::PredType::NATIVE_UINT64, metadata.seed);
  write_scalar(root, "rtol", H5::PredType::NATIVE_DOUBLE, metadata.relative_tolerance);
  write_text_attribute(root, "linear_solver", metadata.linear_solver);
  write_scalar(root, "output_interval", H5::PredType::NATIVE_DOUBLE, metadata.output_interval);
  write_scalar(root, "duration", H5::PredType::NATIVE_DOUBLE, metadata.duration);

  file_->datasets.push_back(create_series(root, "time", "s", chunk_samples_));
  buffers_.emplace_back();
  for (const auto& channel : system.channels()) {
    if (!channel.recorded) continue;
    // A part's group sits inside its instance's ("/muscle/maxwell_branch").
    for (std::size_t slash = channel.group.find('/'); slash != std::string::npos;
         slash = channel.group.find('/', slash + 1)) {
      const std::string parent = channel.group.substr(0, slash);
      if (!file_->groups.count(parent))
        file_->groups[parent] = file_->file.createGroup("/" + parent);
    }
    auto [entry, created] = file_->groups.try_emplace(channel.group);
    if (created) entry->second = file_->file.createGroup("/" + channel.group);
    file_->datasets.push_back(
        create_series(entry->second, channel.name, channel.unit, chunk_samples_));
    signal_indices_.push_back(channel.signal_index);
    buffers_.emplace_back();
  }
  for (auto& buffer : buffers_) buffer.reserve(chunk_samples_);

  H5::Group inputs = file_->file.createGroup("/inputs");
  const auto& slots = system.signal_slots();
  for (std::size_t s = 0; s < slots.size(); ++s) {
    H5::Group group = inputs.createGroup(slots[s].group + "." + slots[s].name);
    write_text_attribute(group, "units", slots[s].unit);
    write_description(group, context.signal(static_cast<int>(s)).describe());
  }
}

Hdf5Recorder::~Hdf5Recorder() {
  if (closed_) return;
  // Neither finished nor failed (an exception unwound past us): leave nothing behind.
  try {
    file_.reset();
  } catch (...) {
  }
  std::error_code ignored;
  std::filesystem::remove(partial_path(path_), ignored);
}

void Hdf5Recorder::record(double time, std::span<const double> signals) {
  buffers_[0].push_back(time);
  for (std::size_t k = 0; k < signal_indices_.size(); ++k) {
    buffers_[k + 1].push_back(signals[static_cast<std::size_t>(signal_indices_[k])]);
  }
  if (buffers_[0].size() >= chunk_samples_) flush();
}

void Hdf5Recorder::flush() {
  const hsize_t count = buffers_[0].size();
  if (count == 0) return;
  const hsize_t offset = written_, total = written_ + count;
  for (std::size_t k = 0; k < buffers_.size(); ++k) {
    H5::DataSet& dataset = file_->datasets[k];
    dataset.extend(&total);
    H5::DataSpace file_space = dataset.getSpace();
    file_space.selectHyperslab(H5S_SELECT_SET, &count, &offset);
    H5::DataSpace memory_space(1, &count);
    dataset.write(buffers_[k].data(), H5::PredType::NATIVE_DOUBLE, memory_space, file_space);
    buffers_[k].clear();
  }
  written_ = total;
}

void Hdf5Recorder::close_with(const std::string& status, const std::string& reason,
                              const SolverStatistics& statistics) {
  flush();
  H5::Group root = file_->file.openGroup("/");
  write_text_attribute(root, "status", status);
  if (!reason.empty()) write_text_attribute(root, "failure", reason);
  write_statistics(root, statistics);
  root.close();
  file_.reset();
  closed_ = true;
}

void Hdf5Recorder::finish(const SolverStatistics& statistics) {
  close_with("complete", "", statistics);
  std::filesystem::rename(partial_path(path_), path_);
}

std::string Hdf5Recorder::fail(const std::string& reason, const SolverStatistics& statistics) {
  close_with("failed", reason, statistics);
  const std::string failed = failed_path(path_);
  std::filesystem::rename(partial_path(path_), failed);
  return failed;
}

}  // namespace tcpmsim
