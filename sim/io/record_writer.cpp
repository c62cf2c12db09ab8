#include "sim/io/record_writer.h"

#include <algorithm>
#include <stdexcept>

#include "sim/io/hdf5_files.h"
#include "sim/io/record_layout.h"
#include "tcpmsim/version.h"

namespace tcpmsim {

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

// The unit of a description's array: times and frequencies by their names, the signal's values
// in the signal's unit. Throws std::logic_error for an array no signal is known to describe, so
// that a new signal's arrays get their unit here (every record's test runs every signal kind).
std::string description_array_unit(const std::string& array, const std::string& signal_unit) {
  if (array == "times" || array == "starts" || array == "start_times") return "s";
  if (array == "frequencies") return "Hz";
  if (array == "phases") return "rad";
  if (array == "values" || array == "amplitudes") return signal_unit;
  throw std::logic_error("the signal description's array '" + array + "' has no unit");
}

void write_description(H5::Group& group, const SignalDescription& description,
                       const std::string& unit) {
  write_text_attribute(group, "type", description.type);
  for (const auto& [name, value] : description.parameters) {
    write_scalar(group, name, H5::PredType::NATIVE_DOUBLE, value);
  }
  for (const auto& [name, values] : description.arrays) {
    H5::DataSet dataset = write_array(group, name, values);
    write_text_attribute(dataset, "units", description_array_unit(name, unit));
  }
  for (const auto& [name, part] : description.parts) {
    H5::Group child = group.createGroup(name);
    write_description(child, part, unit);
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
  if (statistics.linear_iterations > 0)  // GMRES's; direct solvers' records stay as they were
    write_scalar(root, "solver_linear_iterations", type,
                 std::int64_t{statistics.linear_iterations});
  write_scalar(root, "solver_segments", type, std::int64_t{statistics.segments});
  write_scalar(root, "solver_events", type, std::int64_t{statistics.events});
  write_scalar(root, "samples", type, std::int64_t{statistics.output_samples});
}

}  // namespace

void write_ending(H5::H5Object& root, const RecordEnding& ending) {
  write_text_attribute(root, "status", ending.status);
  if (ending.status == "interrupted") {
    write_text_attribute(root, "interruption", ending.reason);
    write_scalar(root, "time_reached", H5::PredType::NATIVE_DOUBLE, ending.time_reached);
  } else if (!ending.reason.empty()) {
    write_text_attribute(root, "failure", ending.reason);
  }
}

namespace {

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

RecordPlan plan_record(const System& system, const Context& context, const RecordMetadata& metadata,
                       std::size_t chunk_samples, std::vector<std::vector<int>>& columns) {
  RecordPlan plan;
  plan.metadata = metadata;
  plan.chunk_samples = chunk_samples;
  columns.emplace_back();
  for (auto& series : record_layout(system)) {
    plan.series.push_back(
        {series.group, series.name, series.unit, series.signal_indices.size(), series.members});
    columns.push_back(std::move(series.signal_indices));
  }
  plan.member_sets = system.member_sets();
  // /inputs: each prescribed signal's description; a member set's signal once, with a
  // `members` attribute, when every member has it alike (one per member otherwise).
  const auto& slots = system.signal_slots();
  const auto input = [&](const std::string& input_path, int slot,
                         std::vector<std::string> members = {}) {
    plan.inputs.push_back({input_path, slots[static_cast<std::size_t>(slot)].unit,
                           context.signal(slot).describe(), std::move(members)});
  };
  for (const auto& entry : input_layout(system)) {
    if (entry.members.empty()) {
      input(entry.path, entry.slots.front());
      continue;
    }
    const SignalDescription first = context.signal(entry.slots.front()).describe();
    bool alike = true;
    for (const int slot : entry.slots) alike = alike && context.signal(slot).describe() == first;
    if (alike) {
      input(entry.path, entry.slots.front(), entry.members);
      continue;
    }
    for (const int slot : entry.slots) {
      const SignalSlot& own = slots[static_cast<std::size_t>(slot)];
      input(own.group + "." + own.name, slot);
    }
  }
  return plan;
}

RecordWriter::RecordWriter(const std::string& path, std::shared_ptr<const RecordPlan> plan) {
  {
    const std::lock_guard lock(hdf5_mutex());
    H5::Exception::dontPrint();
    create_parent_directories(path);
    file_ = H5::H5File(path, H5F_ACC_TRUNC);
  }
  thread_ = std::thread([this, plan] { run(*plan); });
}

RecordWriter::~RecordWriter() {
  if (thread_.joinable()) {
    {
      const std::lock_guard lock(mutex_);
      aborting_ = true;
    }
    changed_.notify_all();
    thread_.join();
  }
  const std::lock_guard lock(hdf5_mutex());
  datasets_.clear();
  try {
    file_.close();
  } catch (...) {
  }
}

void RecordWriter::push(std::vector<std::vector<double>> buffers) {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [&] { return queue_.size() < 2 || error_; });
  if (error_) std::rethrow_exception(error_);
  queue_.push_back(std::move(buffers));
  changed_.notify_all();
}

void RecordWriter::close(std::vector<std::vector<double>> last, const RecordEnding& ending,
                         const SolverStatistics& statistics) {
  {
    const std::lock_guard lock(mutex_);
    if (!last.empty() && !last[0].empty()) queue_.push_back(std::move(last));
    closing_ = true;
    ending_ = ending;
    statistics_ = statistics;
  }
  changed_.notify_all();
  thread_.join();
  if (error_) std::rethrow_exception(error_);
}

void RecordWriter::run(const RecordPlan& plan) {
  try {
    create(plan);
  } catch (...) {
    const std::lock_guard lock(mutex_);
    error_ = std::current_exception();
  }
  for (;;) {
    std::vector<std::vector<double>> buffers;
    {
      std::unique_lock lock(mutex_);
      changed_.wait(lock, [&] { return !queue_.empty() || closing_ || aborting_; });
      if (aborting_) return;
      if (queue_.empty()) break;  // closing, everything written
      buffers = std::move(queue_.front());
      queue_.pop_front();
      changed_.notify_all();  // room for the recorder's next buffers
    }
    if (error_) continue;  // after a failure, drop what comes (the recorder reports it)
    try {
      write(buffers);
    } catch (...) {
      const std::lock_guard lock(mutex_);
      error_ = std::current_exception();
    }
  }
  try {
    if (!error_) close_file();
  } catch (...) {
    const std::lock_guard lock(mutex_);
    error_ = std::current_exception();
  }
}

void RecordWriter::create(const RecordPlan& plan) {
  const std::lock_guard lock(hdf5_mutex());
  const RecordMetadata& metadata = plan.metadata;
  H5::Group root = file_.openGroup("/");
  write_text_attribute(root, "tcpmsim_version", kVersion);
  write_text_attribute(root, "git_commit", kGitCommit);
  write_text_attribute(root, "scenario", metadata.scenario_name);
  write_text_attribute(root, "config_file", metadata.config_file);
  write_text_attribute(root, "config", metadata.resolved_config);
  if (!metadata.command_line.empty())
    write_text_attribute(root, "command_line", metadata.command_line);
  write_scalar(root, "seed", H5::PredType::NATIVE_UINT64, metadata.seed);
  write_scalar(root, "rtol", H5::PredType::NATIVE_DOUBLE, metadata.relative_tolerance);
  write_text_attribute(root, "linear_solver", metadata.linear_solver);
  write_scalar(root, "output_interval", H5::PredType::NATIVE_DOUBLE, metadata.output_interval);
  write_scalar(root, "duration", H5::PredType::NATIVE_DOUBLE, metadata.duration);
  const int level = metadata.compression_level;
  datasets_.push_back(create_series(root, "time", "s", plan.chunk_samples, 1, false, level));
  for (const auto& series : plan.series) {
    // A part's group sits inside its instance's ("/muscle/maxwell_branch").
    H5::Group group = group_at(file_, "/" + series.group);
    H5::DataSet dataset = create_series(group, series.name, series.unit, plan.chunk_samples,
                                        series.columns, !series.members.empty(), level);
    if (!series.members.empty()) write_text_array_attribute(dataset, "members", series.members);
    datasets_.push_back(dataset);
  }
  // /<set>/<property>: a member set's fixed facts, a value per member.
  for (const auto& set : plan.member_sets) {
    for (const auto& property : set.properties) {
      H5::Group group = group_at(file_, "/" + set.name);
      H5::DataSet dataset = write_array(group, property.name, property.values);
      write_text_attribute(dataset, "units", property.unit);
      write_text_array_attribute(dataset, "members", set.members);
    }
  }
  file_.createGroup("/inputs");
  for (const auto& input : plan.inputs) {
    H5::Group group = group_at(file_, "/inputs/" + input.path);
    write_text_attribute(group, "units", input.unit);
    write_description(group, input.description, input.unit);
    if (!input.members.empty()) write_text_array_attribute(group, "members", input.members);
  }
  file_.flush(H5F_SCOPE_GLOBAL);  // a run killed from here on leaves a file that opens
  last_flush_ = std::chrono::steady_clock::now();
}

void RecordWriter::write(const std::vector<std::vector<double>>& buffers) {
  const std::lock_guard lock(hdf5_mutex());
  const hsize_t count = buffers[0].size();
  if (count == 0) return;
  const hsize_t total = written_ + count;
  for (std::size_t k = 0; k < buffers.size(); ++k) {
    H5::DataSet& dataset = datasets_[k];
    const hsize_t columns = k == 0 ? 1 : buffers[k].size() / count;
    const int rank = dataset.getSpace().getSimpleExtentNdims();
    const hsize_t extent[2] = {total, columns}, offset[2] = {written_, 0},
                  block[2] = {count, columns};
    dataset.extend(extent);
    H5::DataSpace file_space = dataset.getSpace();
    file_space.selectHyperslab(H5S_SELECT_SET, block, offset);
    H5::DataSpace memory_space(rank, block);
    dataset.write(buffers[k].data(), H5::PredType::NATIVE_DOUBLE, memory_space, file_space);
  }
  written_ = total;
  const auto now = std::chrono::steady_clock::now();
  if (std::chrono::duration<double>(now - last_flush_).count() >= kFlushSeconds) {
    file_.flush(H5F_SCOPE_GLOBAL);
    last_flush_ = now;
  }
}

void RecordWriter::close_file() {
  const std::lock_guard lock(hdf5_mutex());
  H5::Group root = file_.openGroup("/");
  write_ending(root, ending_);
  write_statistics(root, statistics_);
  root.close();
  datasets_.clear();
  file_.close();
}

}  // namespace tcpmsim
