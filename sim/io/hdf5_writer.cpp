#include "sim/io/hdf5_writer.h"

#include "tcpmsim/version.h"

#include <H5Cpp.h>

#include <filesystem>
#include <stdexcept>

#include "sim/io/hdf5_files.h"

namespace tcpmsim {

struct Hdf5Writer::File {
  H5::H5File file;
};

namespace {

// Runs an HDF5 action, turning the library's exceptions (not std::exceptions) into one.
template <typename Action>
void guarded(const std::string& path, Action&& action) {
  const std::lock_guard lock(hdf5_mutex());
  try {
    action();
  } catch (const H5::Exception& error) {
    throw std::runtime_error("cannot write " + path + ": HDF5 " + error.getFuncName() + ": " +
                             error.getDetailMsg());
  }
}

// Opens or creates every group on the way to `dataset` and returns the parent group.
H5::Group parent_group(H5::H5File& file, const std::string& dataset) {
  H5::Group group = file.openGroup("/");
  const auto slash = dataset.find_last_of('/');
  const std::string parents = slash == std::string::npos ? "" : dataset.substr(0, slash);
  std::string walked;
  std::size_t start = 0;
  while (start < parents.size()) {
    std::size_t end = parents.find('/', start);
    if (end == std::string::npos) end = parents.size();
    const std::string part = parents.substr(start, end - start);
    if (!part.empty()) {
      walked += "/" + part;
      group = file.nameExists(walked) ? file.openGroup(walked) : file.createGroup(walked);
    }
    start = end + 1;
  }
  return group;
}

std::string leaf(const std::string& dataset) {
  const auto slash = dataset.find_last_of('/');
  return slash == std::string::npos ? dataset : dataset.substr(slash + 1);
}

}  // namespace

Hdf5Writer::Hdf5Writer(std::string path) : path_(std::move(path)), file_(std::make_unique<File>()) {
  prepare_output_file(path_);
  guarded(path_, [&] {
    H5::Exception::dontPrint();
    file_->file = H5::H5File(partial_path(path_), H5F_ACC_TRUNC);
  });
}

Hdf5Writer::~Hdf5Writer() {
  const std::lock_guard lock(hdf5_mutex());
  if (committed_) {
    file_.reset();
    return;
  }
  try {
    file_.reset();
  } catch (...) {
  }
  std::error_code ignored;
  std::filesystem::remove(partial_path(path_), ignored);
}

void Hdf5Writer::write(const std::string& dataset, std::span<const double> values,
                       const std::string& units) {
  write_matrix(dataset, values, values.size(), 1, units);
}

void Hdf5Writer::write_matrix(const std::string& dataset, std::span<const double> row_major,
                              std::size_t rows, std::size_t columns, const std::string& units) {
  if (row_major.size() != rows * columns) {
    throw std::logic_error("Hdf5Writer: " + dataset + " has the wrong number of values");
  }
  guarded(path_, [&] {
    H5::Group group = parent_group(file_->file, dataset);
    const hsize_t dimensions[2] = {rows, columns};
    H5::DataSpace space(columns == 1 ? 1 : 2, dimensions);
    H5::DataSet set = group.createDataSet(leaf(dataset), H5::PredType::NATIVE_DOUBLE, space);
    if (!row_major.empty()) set.write(row_major.data(), H5::PredType::NATIVE_DOUBLE);
    write_text_attribute(set, "units", units);
  });
}

void Hdf5Writer::write_scalar(const std::string& dataset, double value, const std::string& units) {
  guarded(path_, [&] {
    H5::Group group = parent_group(file_->file, dataset);
    H5::DataSet set =
        group.createDataSet(leaf(dataset), H5::PredType::NATIVE_DOUBLE, H5::DataSpace(H5S_SCALAR));
    set.write(&value, H5::PredType::NATIVE_DOUBLE);
    write_text_attribute(set, "units", units);
  });
}

void Hdf5Writer::write_strings(const std::string& dataset, const std::vector<std::string>& values) {
  guarded(path_, [&] {
    H5::Group group = parent_group(file_->file, dataset);
    const H5::StrType type = utf8_text_type();
    const hsize_t size = values.size();
    H5::DataSet set = group.createDataSet(leaf(dataset), type, H5::DataSpace(1, &size));
    if (!values.empty()) set.write(c_strings(values).data(), type);
  });
}

void Hdf5Writer::write_integers(const std::string& dataset, std::span<const long long> values) {
  guarded(path_, [&] {
    H5::Group group = parent_group(file_->file, dataset);
    const hsize_t size = values.size();
    H5::DataSet set =
        group.createDataSet(leaf(dataset), H5::PredType::NATIVE_LLONG, H5::DataSpace(1, &size));
    if (!values.empty()) set.write(values.data(), H5::PredType::NATIVE_LLONG);
    write_text_attribute(set, "units", "1");  // counts and identifiers
  });
}

void Hdf5Writer::attribute(const std::string& object, const std::string& name,
                           const std::string& value) {
  guarded(path_, [&] {
    if (object == "/") {
      H5::Group root = file_->file.openGroup("/");
      write_text_attribute(root, name, value);
    } else if (file_->file.childObjType(object) == H5O_TYPE_GROUP) {
      H5::Group group = file_->file.openGroup(object);
      write_text_attribute(group, name, value);
    } else {
      H5::DataSet set = file_->file.openDataSet(object);
      write_text_attribute(set, name, value);
    }
  });
}

void Hdf5Writer::provenance(const Provenance& provenance) {
  std::vector<std::string> files, configs, seeds;
  for (const auto& config : provenance.configs) {
    files.push_back(config.file);
    configs.push_back(config.resolved);
    seeds.push_back(config.seed);
  }
  guarded(path_, [&] {
    H5::Group root = file_->file.openGroup("/");
    write_text_attribute(root, "command_line", provenance.command_line);
    if (files.empty()) return;
    write_text_array_attribute(root, "config_files", files);
    write_text_array_attribute(root, "configs", configs);
    write_text_array_attribute(root, "seeds", seeds);
  });
}

void Hdf5Writer::commit() {
  guarded(path_, [&] {
    H5::Group root = file_->file.openGroup("/");
    if (!root.attrExists("tcpmsim_version"))
      write_text_attribute(root, "tcpmsim_version", kVersion);
    if (!root.attrExists("git_commit")) write_text_attribute(root, "git_commit", kGitCommit);
    file_->file.close();
  });
  std::error_code error;
  std::filesystem::rename(partial_path(path_), path_, error);
  if (error) throw std::runtime_error("cannot write " + path_ + ": " + error.message());
  committed_ = true;
}

}  // namespace tcpmsim
