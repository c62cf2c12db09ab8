#include "sim/io/hdf5_recorder.h"

#include <H5Cpp.h>

#include <algorithm>
#include <filesystem>

#include "sim/io/hdf5_files.h"
#include "sim/io/record_layout.h"
#include "sim/signal.h"
#include "tcpmsim/version.h"

namespace tcpmsim {

struct Hdf5Recorder::File {
  H5::H5File file;
  std::vector<H5::DataSet> datasets;  // [0] is /time
};

namespace {

template <typename T>
void write_scalar(H5::H5Object& object, const std::string& name, const H5::PredType& type,
                  T value) {
  H5::Attribute attribute = object.createAttribute(name, type, H5::DataSpace(H5S_SCALAR));
  attribute.write(type, &value);
}

// A series of one number per time (1-D), or of a member set's `columns` (time x column, even for
// one member). A 2-D chunk holds about as many numbers as a 1-D one.
H5::DataSet create_series(H5::Group& parent, const std::string& name, const std::string& units,
                          std::size_t chunk, std::size_t columns, bool matrix,
                          int compression_level) {
  const int rank = matrix ? 2 : 1;
  const hsize_t initial[2] = {0, columns}, maximum[2] = {H5S_UNLIMITED, columns};
  const hsize_t chunk_size[2] = {std::max<hsize_t>(1, chunk / columns), columns};
  H5::DataSpace space(rank, initial, maximum);
  H5::DSetCreatPropList properties;
  properties.setChunk(rank, chunk_size);
  if (compression_level > 0) {
    properties.setShuffle();
    properties.setDeflate(compression_level);
  }
  H5::DataSet dataset = parent.createDataSet(name, H5::PredType::NATIVE_DOUBLE, space, properties);
  write_text_attribute(dataset, "units", units);
  return dataset;
}

H5::DataSet write_array(H5::Group& parent, const std::string& name,
                        const std::vector<double>& values) {
  const hsize_t size = values.size();
  H5::DataSet dataset =
      parent.createDataSet(name, H5::PredType::NATIVE_DOUBLE, H5::DataSpace(1, &size));
  if (!values.empty()) dataset.write(values.data(), H5::PredType::NATIVE_DOUBLE);
  return dataset;
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

// The group at `path` ("/muscle/maxwell_branch", "/inputs/b/drive.power"), created with the
// groups above it where they do not exist yet.
H5::Group group_at(H5::H5File& file, const std::string& path) {
  for (std::size_t slash = path.find('/', 1); slash != std::string::npos;
       slash = path.find('/', slash + 1)) {
    const std::string parent = path.substr(0, slash);
    if (!file.nameExists(parent)) file.createGroup(parent);
  }
  return file.nameExists(path) ? file.openGroup(path) : file.createGroup(path);
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
    : path_(std::move(path)),
      file_(std::make_unique<File>()),
      chunk_samples_(chunk_samples),
      compression_level_(metadata.compression_level) {
  const std::lock_guard lock(hdf5_mutex());
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

  file_->datasets.push_back(
      create_series(root, "time", "s", chunk_samples_, 1, false, compression_level_));
  columns_.emplace_back();
  for (auto& series : record_layout(system)) {
    // A part's group sits inside its instance's ("/muscle/maxwell_branch").
    H5::Group group = group_at(file_->file, "/" + series.group);
    H5::DataSet dataset =
        create_series(group, series.name, series.unit, chunk_samples_, series.signal_indices.size(),
                      !series.members.empty(), compression_level_);
    if (!series.members.empty()) write_text_array_attribute(dataset, "members", series.members);
    file_->datasets.push_back(dataset);
    columns_.push_back(std::move(series.signal_indices));
  }
  std::size_t width = 1;
  for (const auto& columns : columns_) width += columns.size();
  // Rows buffered before a write: a chunk's worth, or fewer when the record is wide, so that
  // the buffers stay near kBufferedValues numbers whatever the bundle's size.
  flush_rows_ = std::max<std::size_t>(1, std::min(chunk_samples_, kBufferedValues / width));
  buffers_.resize(columns_.size());
  for (std::size_t k = 0; k < buffers_.size(); ++k)
    buffers_[k].reserve(flush_rows_ * std::max<std::size_t>(1, columns_[k].size()));

  write_member_properties(system);
  write_inputs(system, context);
}

// /<set>/<property>: a member set's fixed facts, a value per member.
void Hdf5Recorder::write_member_properties(const System& system) {
  for (const auto& set : system.member_sets()) {
    for (const auto& property : set.properties) {
      H5::Group group = group_at(file_->file, "/" + set.name);
      H5::DataSet dataset = write_array(group, property.name, property.values);
      write_text_attribute(dataset, "units", property.unit);
      write_text_array_attribute(dataset, "members", set.members);
    }
  }
}

// /inputs: each prescribed signal's description; a member set's signal once, with a `members`
// attribute, when every member has it alike (one per member otherwise).
void Hdf5Recorder::write_inputs(const System& system, const Context& context) {
  file_->file.createGroup("/inputs");
  const auto& slots = system.signal_slots();
  auto write = [&](const std::string& path, int slot) {
    H5::Group group = group_at(file_->file, "/inputs/" + path);
    write_text_attribute(group, "units", slots[static_cast<std::size_t>(slot)].unit);
    write_description(group, context.signal(slot).describe());
    return group;
  };
  for (const auto& entry : input_layout(system)) {
    if (entry.members.empty()) {
      write(entry.path, entry.slots.front());
      continue;
    }
    const SignalDescription first = context.signal(entry.slots.front()).describe();
    bool alike = true;
    for (const int slot : entry.slots) alike = alike && context.signal(slot).describe() == first;
    if (alike) {
      H5::Group group = write(entry.path, entry.slots.front());
      write_text_array_attribute(group, "members", entry.members);
      continue;
    }
    for (const int slot : entry.slots) {
      const SignalSlot& own = slots[static_cast<std::size_t>(slot)];
      write(own.group + "." + own.name, slot);
    }
  }
}

Hdf5Recorder::~Hdf5Recorder() {
  const std::lock_guard lock(hdf5_mutex());
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
  for (std::size_t k = 1; k < buffers_.size(); ++k) {
    for (const int index : columns_[k])
      buffers_[k].push_back(signals[static_cast<std::size_t>(index)]);
  }
  if (buffers_[0].size() >= flush_rows_) flush();
}

void Hdf5Recorder::flush() {
  const std::lock_guard lock(hdf5_mutex());
  const hsize_t count = buffers_[0].size();
  if (count == 0) return;
  const hsize_t total = written_ + count;
  for (std::size_t k = 0; k < buffers_.size(); ++k) {
    H5::DataSet& dataset = file_->datasets[k];
    const hsize_t columns = k == 0 ? 1 : columns_[k].size();
    const int rank = dataset.getSpace().getSimpleExtentNdims();
    const hsize_t extent[2] = {total, columns}, offset[2] = {written_, 0},
                  block[2] = {count, columns};
    dataset.extend(extent);
    H5::DataSpace file_space = dataset.getSpace();
    file_space.selectHyperslab(H5S_SELECT_SET, block, offset);
    H5::DataSpace memory_space(rank, block);
    dataset.write(buffers_[k].data(), H5::PredType::NATIVE_DOUBLE, memory_space, file_space);
    buffers_[k].clear();
  }
  written_ = total;
}

void Hdf5Recorder::close_with(const std::string& status, const std::string& reason,
                              const SolverStatistics& statistics) {
  const std::lock_guard lock(hdf5_mutex());
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
