#pragma once

#include <H5Cpp.h>

#include <filesystem>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

// What the HDF5 record and the analysis writers share about files: where a file lives until it
// is complete, its directories, and text attributes.
namespace tcpmsim {

// The one lock every HDF5 call of tcpmsim holds. The library keeps process-wide state, and its
// C++ layer is not made for several threads, so two threads writing two records (a batch of
// runs, a sweep's part files) take turns in the library, while their integrations run at once.
// Recursive: a locked writer may call another locked helper.
std::recursive_mutex& hdf5_mutex();

// "<path>.partial": the name a file is written under, renamed to `path` only when complete.
std::string partial_path(const std::string& path);

// Creates the directories above `path`; a failure is a std::runtime_error naming `path`.
void create_parent_directories(const std::string& path);

// Checks, before any work, that a file can be put at `path`: it must be a regular file or not
// exist (a directory, a path ending in '/' or a device is refused), and its directories are
// created. A failure is a
// std::runtime_error naming `path` and the reason.
void check_output_path(const std::string& path);

// Makes sure a file can be written at `path` through its partial file, before any work:
// check_output_path, then the partial file is created empty. A failure is a std::runtime_error
// naming the file concerned and the system's reason ("Permission denied").
void prepare_output_file(const std::string& path);

// Variable-length UTF-8 text, the type of every string the records and reports write.
H5::StrType utf8_text_type();
// Pointers to `values`' characters, for writing them as variable-length texts.
std::vector<const char*> c_strings(const std::vector<std::string>& values);

// A scalar UTF-8 text attribute.
void write_text_attribute(H5::H5Object& object, const std::string& name, const std::string& value);
// A 1-D array of UTF-8 texts as an attribute (a bundle's member names).
void write_text_array_attribute(H5::H5Object& object, const std::string& name,
                                const std::vector<std::string>& values);

// A dataset's values as doubles, whatever its shape (row-major).
std::vector<double> read_doubles(const H5::H5Location& location, const std::string& name);
// A dataset of variable-length texts, whatever its shape (row-major); a null text reads as "".
std::vector<std::string> read_texts(const H5::H5Location& location, const std::string& name);
// A scalar text attribute, or empty when there is none (or it is not text). An attribute of
// more than one value is an H5::AttributeIException, as a damaged file's.
std::string read_text_attribute(const H5::H5Object& object, const std::string& name);
// Throws H5::AttributeIException unless `attribute` holds exactly one value: reading one of
// several into a single value would write past it (a crafted or damaged file).
void require_single_value(const H5::Attribute& attribute);
// A dataset's "units" attribute, or empty.
std::string units_of(const H5::H5Object& object);

// Runs `write`, which writes the record at `path`, turning the HDF5 library's and the file
// system's exceptions into std::runtime_error naming the file.
template <typename Write>
decltype(auto) writing_record(const std::string& path, Write&& write) {
  try {
    return write();
  } catch (const H5::Exception& error) {
    throw std::runtime_error("cannot write " + path + ": HDF5 " + error.getFuncName() + ": " +
                             error.getDetailMsg());
  } catch (const std::filesystem::filesystem_error& error) {
    throw std::runtime_error(std::string("cannot write the output: ") + error.what());
  }
}

}  // namespace tcpmsim
