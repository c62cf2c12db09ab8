#include "sim/io/record_recovery.h"

#include <H5Cpp.h>

#include <algorithm>
#include <filesystem>
#include <stdexcept>
#include <vector>

#include "sim/config/config_error.h"
#include "sim/io/hdf5_files.h"
#include "sim/io/hdf5_recorder.h"
#include "sim/io/record_writer.h"

namespace tcpmsim {

namespace {

constexpr const char* kSuffix = ".partial";

[[noreturn]] void refuse(const std::string& partial, const std::string& problem) {
  throw ConfigError(SourceLocation{partial, 0, 0, ""}, "", problem);
}

// Every dataset of the file whose first dimension is unlimited: /time and the series.
void collect_series(H5::Group& group, const std::string& path, std::vector<H5::DataSet>& found) {
  for (hsize_t i = 0; i < group.getNumObjs(); ++i) {
    const std::string name = group.getObjnameByIdx(i);
    const std::string child = path + "/" + name;
    const H5O_type_t type = group.childObjType(name);
    if (type == H5O_TYPE_GROUP) {
      H5::Group inner = group.openGroup(name);
      collect_series(inner, child, found);
    } else if (type == H5O_TYPE_DATASET) {
      H5::DataSet dataset = group.openDataSet(name);
      const H5::DataSpace space = dataset.getSpace();
      hsize_t dims[2] = {0, 0}, max[2] = {0, 0};
      if (space.getSimpleExtentNdims() < 1 || space.getSimpleExtentNdims() > 2) continue;
      space.getSimpleExtentDims(dims, max);
      if (max[0] == H5S_UNLIMITED) found.push_back(dataset);
    }
  }
}

hsize_t rows_of(const H5::DataSet& dataset) {
  hsize_t dims[2] = {0, 0};
  dataset.getSpace().getSimpleExtentDims(dims);
  return dims[0];
}

// The samples every series holds whose times increase: what the last flush left whole.
hsize_t complete_rows(H5::H5File& file, const std::vector<H5::DataSet>& series) {
  hsize_t rows = rows_of(file.openDataSet("time"));
  for (const auto& dataset : series) rows = std::min(rows, rows_of(dataset));
  const std::vector<double> time = read_doubles(file, "time");
  for (hsize_t k = 1; k < rows; ++k) {
    if (!(time[k] > time[k - 1])) return k;
  }
  return rows;
}

// Cuts every series of the open record to its last whole flush and closes it as interrupted.
RecoveredRecord cut_open_record(H5::H5File& file, const std::string& partial) {
  H5::Group root = file.openGroup("/");
  // A record states what made it when it is created, before its first sample.
  for (const char* attribute : {"tcpmsim_version", "config"}) {
    if (!root.attrExists(attribute))
      refuse(partial, std::string("not a tcpmsim record: it has no '") + attribute +
                          "' attribute (tcpmsim writes it when it creates a record)");
  }
  if (!file.nameExists("time")) refuse(partial, "not a tcpmsim record: no /time dataset");
  if (root.attrExists("status")) {
    refuse(partial, "the record already has a status (it was closed): nothing to recover");
  }
  std::vector<H5::DataSet> series;
  collect_series(root, "", series);
  const hsize_t rows = complete_rows(file, series);
  for (auto& dataset : series) {
    hsize_t dims[2] = {0, 0};
    dataset.getSpace().getSimpleExtentDims(dims);
    dims[0] = rows;
    dataset.extend(dims);
  }
  RecoveredRecord recovered;
  recovered.samples = static_cast<long>(rows);
  if (rows > 0) recovered.time_reached = read_doubles(file, "time").back();
  write_ending(root, {"interrupted",
                      "the run ended without closing its record (killed, or the machine "
                      "stopped); recovered by tcpmsim recover up to the last flush",
                      recovered.time_reached});
  const long samples = recovered.samples;
  H5::Attribute attribute =
      root.createAttribute("samples", H5::PredType::NATIVE_INT64, H5::DataSpace(H5S_SCALAR));
  attribute.write(H5::PredType::NATIVE_INT64, &samples);
  attribute.close();
  root.close();
  file.close();
  return recovered;
}

RecoveredRecord cut_and_close(const std::string& partial, const std::string& working) {
  const std::lock_guard lock(hdf5_mutex());
  H5::Exception::dontPrint();
  H5::H5File file;
  try {
    file = H5::H5File(working, H5F_ACC_RDWR);
  } catch (const H5::Exception&) {
    refuse(partial,
           "cannot read it as HDF5: the run was killed before its first flush, or "
           "this is not a tcpmsim record");
  }
  // Past the header, a file damaged inside (or a record of another shape) fails in the library.
  try {
    return cut_open_record(file, partial);
  } catch (const H5::Exception& error) {
    refuse(partial, "cannot recover it: " + error.getDetailMsg() +
                        " (the file is damaged, or not a record tcpmsim wrote)");
  }
}

}  // namespace

RecoveredRecord recover_partial_record(const std::string& partial, const std::string& output) {
  if (!std::filesystem::is_regular_file(partial)) refuse(partial, "no such file");
  if (std::filesystem::file_size(partial) == 0) {
    // A sweep's runs are kept in <out>.parts, not in its partial file.
    const bool sweep =
        partial.ends_with(kSuffix) &&
        std::filesystem::is_directory(
            partial.substr(0, partial.size() - std::char_traits<char>::length(kSuffix)) + ".parts");
    refuse(partial, sweep ? "it is empty: a sweep writes its file when it ends, and keeps its runs "
                            "in the .parts directory beside it; tcpmsim sweep ... --resume "
                            "finishes it"
                          : "it is empty: the run was stopped before it wrote anything");
  }
  std::string target = output;
  if (target.empty()) {
    const bool named =
        partial.size() > std::char_traits<char>::length(kSuffix) && partial.ends_with(kSuffix);
    if (!named) refuse(partial, "expected a '<out>.partial' file (or give the output with -o)");
    target = Hdf5Recorder::interrupted_path(
        partial.substr(0, partial.size() - std::char_traits<char>::length(kSuffix)));
  }
  if (std::filesystem::exists(target)) {
    throw std::runtime_error("cannot write " + target + ": it exists (a record is never replaced)");
  }
  // Worked on as a copy, so that the partial file stays as it was until the record is whole.
  const std::string working = target + ".recovering";
  create_parent_directories(target);
  std::filesystem::copy_file(partial, working, std::filesystem::copy_options::overwrite_existing);
  RecoveredRecord recovered;
  try {
    recovered = cut_and_close(partial, working);
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(working, ignored);
    throw;
  }
  std::filesystem::rename(working, target);
  std::filesystem::remove(partial);
  recovered.path = target;
  return recovered;
}

}  // namespace tcpmsim
