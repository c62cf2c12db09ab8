#include "sim/io/hdf5_recorder.h"

#include <algorithm>
#include <filesystem>

#include "sim/io/hdf5_files.h"

namespace tcpmsim {

namespace {
// "<stem>.<ending>.h5" (the extension of `path` kept when it has one).
std::string ended_path(const std::string& path, const std::string& ending) {
  std::filesystem::path ended(path);
  const std::string extension = ended.extension().string();
  ended.replace_extension("." + ending + (extension.empty() ? std::string(".h5") : extension));
  return ended.string();
}
}  // namespace

std::string Hdf5Recorder::failed_path(const std::string& path) {
  return ended_path(path, "failed");
}

std::string Hdf5Recorder::interrupted_path(const std::string& path) {
  return ended_path(path, "interrupted");
}

Hdf5Recorder::Hdf5Recorder(std::string path, const System& system, const Context& context,
                           const RecordMetadata& metadata, std::size_t chunk_samples)
    : path_(std::move(path)) {
  prepare_output_file(path_);
  auto plan = std::make_shared<const RecordPlan>(
      plan_record(system, context, metadata, chunk_samples, columns_));
  std::size_t width = 1;
  for (const auto& columns : columns_) width += columns.size();
  // Rows buffered before a write: a chunk's worth, or fewer when the record is wide, so that
  // the buffers stay near kBufferedValues numbers whatever the bundle's size.
  flush_rows_ = std::max<std::size_t>(1, std::min(chunk_samples, kBufferedValues / width));
  buffers_.resize(columns_.size());
  for (std::size_t k = 0; k < buffers_.size(); ++k)
    buffers_[k].reserve(flush_rows_ * std::max<std::size_t>(1, columns_[k].size()));

  writer_ = std::make_unique<RecordWriter>(partial_path(path_), std::move(plan));
  last_hand_over_ = std::chrono::steady_clock::now();
}

Hdf5Recorder::~Hdf5Recorder() {
  if (!writer_) return;  // closed
  // Neither finished nor failed (an exception unwound past us): leave nothing behind.
  writer_.reset();
  std::error_code ignored;
  std::filesystem::remove(partial_path(path_), ignored);
}

void Hdf5Recorder::record(double time, std::span<const double> signals) {
  buffers_[0].push_back(time);
  for (std::size_t k = 1; k < buffers_.size(); ++k) {
    for (const int index : columns_[k])
      buffers_[k].push_back(signals[static_cast<std::size_t>(index)]);
  }
  const std::size_t rows = buffers_[0].size();
  // The clock is read at every row (some 20 ns, against the microseconds of the step that made
  // the row): a run that makes a row every few seconds reaches the file within seconds too.
  if (rows >= flush_rows_ ||
      std::chrono::duration<double>(std::chrono::steady_clock::now() - last_hand_over_).count() >=
          kHandOverSeconds) {
    hand_over();
  }
}

void Hdf5Recorder::hand_over() {
  std::vector<std::vector<double>> full(buffers_.size());
  for (std::size_t k = 0; k < buffers_.size(); ++k) {
    full[k].reserve(buffers_[k].capacity());
    full[k].swap(buffers_[k]);
  }
  writer_->push(std::move(full));
  last_hand_over_ = std::chrono::steady_clock::now();
}

void Hdf5Recorder::close_with(const RecordEnding& ending, const SolverStatistics& statistics) {
  // If closing throws, the writer stays, and the destructor removes the partial file.
  writer_->close(std::move(buffers_), ending, statistics);
  writer_.reset();
}

void Hdf5Recorder::finish(const SolverStatistics& statistics) {
  close_with({"complete", "", 0.0}, statistics);
  std::filesystem::rename(partial_path(path_), path_);
}

std::string Hdf5Recorder::fail(const std::string& reason, const SolverStatistics& statistics) {
  close_with({"failed", reason, 0.0}, statistics);
  const std::string failed = failed_path(path_);
  std::filesystem::rename(partial_path(path_), failed);
  return failed;
}

std::string Hdf5Recorder::interrupt(const std::string& reason, double time_reached,
                                    const SolverStatistics& statistics) {
  close_with({"interrupted", reason, time_reached}, statistics);
  const std::string interrupted = interrupted_path(path_);
  std::filesystem::rename(partial_path(path_), interrupted);
  return interrupted;
}

}  // namespace tcpmsim
