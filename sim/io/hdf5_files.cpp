#include "sim/io/hdf5_files.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <vector>

namespace tcpmsim {

std::recursive_mutex& hdf5_mutex() {
  static std::recursive_mutex mutex;  // mirrors the library's own process-wide state
  return mutex;
}

std::string partial_path(const std::string& path) {
  return path + ".partial";
}

void create_parent_directories(const std::string& path) {
  const auto parent = std::filesystem::path(path).parent_path();
  if (parent.empty()) return;
  std::error_code error;
  std::filesystem::create_directories(parent, error);
  if (error) throw std::runtime_error("cannot write " + path + ": " + error.message());
}

void check_output_path(const std::string& path) {
  if (std::filesystem::path(path).filename().empty())
    throw std::runtime_error("cannot write " + path + ": it names a directory (it ends in /)");
  std::error_code error;
  const auto status = std::filesystem::status(path, error);
  if (std::filesystem::is_directory(status)) {
    throw std::runtime_error("cannot write " + path + ": it is a directory");
  }
  if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status)) {
    throw std::runtime_error("cannot write " + path +
                             ": it exists and is not a regular file (a device, pipe or socket)");
  }
  create_parent_directories(path);
}

void prepare_output_file(const std::string& path) {
  check_output_path(path);
  const std::string partial = partial_path(path);
  std::FILE* probe = std::fopen(partial.c_str(), "wb");
  if (!probe) {
    throw std::runtime_error("cannot create " + partial + " (written first, renamed to " + path +
                             " when complete): " + std::strerror(errno));
  }
  std::fclose(probe);
}

H5::StrType utf8_text_type() {
  H5::StrType type(H5::PredType::C_S1, H5T_VARIABLE);
  type.setCset(H5T_CSET_UTF8);
  return type;
}

std::vector<const char*> c_strings(const std::vector<std::string>& values) {
  std::vector<const char*> pointers;
  pointers.reserve(values.size());
  for (const auto& value : values) pointers.push_back(value.c_str());
  return pointers;
}

void write_text_attribute(H5::H5Object& object, const std::string& name, const std::string& value) {
  const H5::StrType type = utf8_text_type();
  H5::Attribute attribute = object.createAttribute(name, type, H5::DataSpace(H5S_SCALAR));
  attribute.write(type, value);
}

void write_text_array_attribute(H5::H5Object& object, const std::string& name,
                                const std::vector<std::string>& values) {
  const H5::StrType type = utf8_text_type();
  const hsize_t size = values.size();
  H5::Attribute attribute = object.createAttribute(name, type, H5::DataSpace(1, &size));
  attribute.write(type, c_strings(values).data());
}

std::vector<double> read_doubles(const H5::H5Location& location, const std::string& name) {
  H5::DataSet set = location.openDataSet(name);
  const H5::DataSpace space = set.getSpace();
  std::vector<double> values(static_cast<std::size_t>(space.getSimpleExtentNpoints()));
  if (!values.empty()) set.read(values.data(), H5::PredType::NATIVE_DOUBLE);
  return values;
}

std::vector<std::string> read_texts(const H5::H5Location& location, const std::string& name) {
  H5::DataSet set = location.openDataSet(name);
  const H5::DataSpace space = set.getSpace();
  std::vector<char*> texts(static_cast<std::size_t>(space.getSimpleExtentNpoints()));
  const H5::StrType type = utf8_text_type();
  if (!texts.empty()) set.read(texts.data(), type);
  std::vector<std::string> values;
  for (const char* text : texts) values.emplace_back(text != nullptr ? text : "");
  if (!texts.empty()) H5::DataSet::vlenReclaim(texts.data(), type, space);
  return values;
}

std::string read_text_attribute(const H5::H5Object& object, const std::string& name) {
  if (!object.attrExists(name)) return "";
  H5::Attribute attribute = object.openAttribute(name);
  if (attribute.getTypeClass() != H5T_STRING) return "";
  require_single_value(attribute);
  std::string value;
  attribute.read(attribute.getStrType(), value);
  return value;
}

void require_single_value(const H5::Attribute& attribute) {
  const hssize_t count = attribute.getSpace().getSimpleExtentNpoints();
  if (count != 1)
    throw H5::AttributeIException("require_single_value", "the attribute " + attribute.getName() +
                                                              " holds " + std::to_string(count) +
                                                              " values where one is expected");
}

std::string units_of(const H5::H5Object& object) {
  return read_text_attribute(object, "units");
}

}  // namespace tcpmsim
