#include "tests/support/record_digest.h"

#include <hdf5.h>

#include <cstdint>
#include <cstdio>
#include <set>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace tcpmsim::testing {

namespace {

const std::set<std::string> kIgnoredAttributes{"tcpmsim_version", "git_commit",   "config_file",
                                               "command_line",    "config_files", "command",
                                               "data_directory",  "spring_files"};

class Hash {
 public:
  void add(const void* data, std::size_t size) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < size; ++i) {
      value_ ^= bytes[i];
      value_ *= 1099511628211ull;
    }
  }
  template <typename T>
  void add_value(T value) {
    add(&value, sizeof value);
  }
  std::string hex() const {
    char text[20];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(value_));
    return text;
  }

 private:
  std::uint64_t value_ = 14695981039346656037ull;
};

// Hashes `count` elements of `type` read by `read` (H5Dread or H5Aread into a buffer).
template <typename Read>
std::string hash_contents(hid_t type, hid_t space, Read read) {
  Hash hash;
  const int rank = H5Sget_simple_extent_ndims(space);
  std::vector<hsize_t> dims(static_cast<std::size_t>(std::max(rank, 0)));
  if (rank > 0) H5Sget_simple_extent_dims(space, dims.data(), nullptr);
  hash.add_value(rank);
  for (hsize_t d : dims) hash.add_value(static_cast<std::uint64_t>(d));
  const auto count = static_cast<std::size_t>(H5Sget_simple_extent_npoints(space));
  const H5T_class_t type_class = H5Tget_class(type);
  hash.add_value(static_cast<int>(type_class));
  if (type_class == H5T_STRING && H5Tis_variable_str(type) > 0) {
    hid_t memory = H5Tcopy(H5T_C_S1);
    H5Tset_size(memory, H5T_VARIABLE);
    H5Tset_cset(memory, H5Tget_cset(type));
    std::vector<char*> strings(count, nullptr);
    if (count > 0 && read(memory, strings.data()) < 0) throw std::runtime_error("cannot read");
    for (char* text : strings) {
      const std::string value = text ? text : "";
      hash.add_value(value.size());
      hash.add(value.data(), value.size());
    }
    if (count > 0) {
      hid_t scalar = H5Screate_simple(1, std::vector<hsize_t>{count}.data(), nullptr);
      H5Dvlen_reclaim(memory, scalar, H5P_DEFAULT, strings.data());
      H5Sclose(scalar);
    }
    H5Tclose(memory);
    return hash.hex();
  }
  hid_t memory = H5Tget_native_type(type, H5T_DIR_ASCEND);
  const std::size_t size = H5Tget_size(memory);
  hash.add_value(static_cast<std::uint64_t>(size));
  std::vector<unsigned char> buffer(count * size);
  if (count > 0 && read(memory, buffer.data()) < 0) throw std::runtime_error("cannot read");
  hash.add(buffer.data(), buffer.size());
  H5Tclose(memory);
  return hash.hex();
}

void digest_attributes(hid_t object, const std::string& path, RecordDigest& digest) {
  const int count = H5Aget_num_attrs(object);
  for (int i = 0; i < count; ++i) {
    hid_t attribute = H5Aopen_by_idx(object, ".", H5_INDEX_NAME, H5_ITER_INC,
                                     static_cast<hsize_t>(i), H5P_DEFAULT, H5P_DEFAULT);
    char name[256];
    H5Aget_name(attribute, sizeof name, name);
    if (!kIgnoredAttributes.count(name)) {
      hid_t type = H5Aget_type(attribute);
      hid_t space = H5Aget_space(attribute);
      digest[path + "@" + name] = hash_contents(type, space, [&](hid_t memory, void* buffer) {
        return H5Aread(attribute, memory, buffer);
      });
      H5Sclose(space);
      H5Tclose(type);
    }
    H5Aclose(attribute);
  }
}

void digest_group(hid_t group, const std::string& path, RecordDigest& digest) {
  digest_attributes(group, path.empty() ? "/" : path, digest);
  H5G_info_t info;
  H5Gget_info(group, &info);
  for (hsize_t i = 0; i < info.nlinks; ++i) {
    char name[512];
    H5Lget_name_by_idx(group, ".", H5_INDEX_NAME, H5_ITER_INC, i, name, sizeof name, H5P_DEFAULT);
    const std::string child = path + "/" + name;
    H5O_info_t object;
    H5Oget_info_by_name(group, name, &object, H5P_DEFAULT);
    if (object.type == H5O_TYPE_GROUP) {
      hid_t inner = H5Gopen(group, name, H5P_DEFAULT);
      digest_group(inner, child, digest);
      H5Gclose(inner);
    } else if (object.type == H5O_TYPE_DATASET) {
      hid_t dataset = H5Dopen(group, name, H5P_DEFAULT);
      hid_t type = H5Dget_type(dataset);
      hid_t space = H5Dget_space(dataset);
      digest[child] = hash_contents(type, space, [&](hid_t memory, void* buffer) {
        return H5Dread(dataset, memory, H5S_ALL, H5S_ALL, H5P_DEFAULT, buffer);
      });
      digest_attributes(dataset, child, digest);
      H5Sclose(space);
      H5Tclose(type);
      H5Dclose(dataset);
    }
  }
}

}  // namespace

RecordDigest record_digest(const std::string& path) {
  hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (file < 0) throw std::runtime_error("cannot open " + path);
  RecordDigest digest;
  hid_t root = H5Gopen(file, "/", H5P_DEFAULT);
  digest_group(root, "", digest);
  H5Gclose(root);
  H5Fclose(file);
  return digest;
}

std::string format_digest(const RecordDigest& digest) {
  std::string text;
  for (const auto& [path, hash] : digest) text += path + " " + hash + "\n";
  return text;
}

RecordDigest parse_digest(const std::string& text) {
  RecordDigest digest;
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    const auto space = line.rfind(' ');
    if (line.empty() || space == std::string::npos) continue;
    digest[line.substr(0, space)] = line.substr(space + 1);
  }
  return digest;
}

}  // namespace tcpmsim::testing
