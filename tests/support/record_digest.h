#pragma once

#include <map>
#include <string>

namespace tcpmsim::testing {

// A fingerprint of every object in an HDF5 file: for each dataset and each attribute, its path
// ("/muscle/force", "/muscle/force@units", "/@seed") and a 64-bit FNV-1a hash of its type class,
// shape and bytes. Two files with the same digest hold the same numbers bit for bit. Attributes
// that name the build or the invocation (tcpmsim_version, git_commit, config_file, and the
// analyses' command, data_directory and spring_files) are left out:
// they differ between builds by design.
using RecordDigest = std::map<std::string, std::string>;
RecordDigest record_digest(const std::string& path);

// "path hash" lines, sorted; and back.
std::string format_digest(const RecordDigest& digest);
RecordDigest parse_digest(const std::string& text);

}  // namespace tcpmsim::testing
