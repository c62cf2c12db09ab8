#pragma once

#include <string>

namespace tcpmsim {

struct RecoveredRecord {
  std::string path;           // the .interrupted.h5 file written
  long samples = 0;           // the samples it holds
  double time_reached = 0.0;  // the last sample's time [s]
};

// Turns the "<out>.partial" file of a run that ended without closing its record (killed with
// SIGKILL, lost power) into "<out stem>.interrupted.h5": every series cut to the samples whose
// times were flushed (the longest run of increasing times that every series holds), status
// "interrupted", `interruption` saying how, `time_reached` and `samples`. The partial file is
// removed once the record is written. `output` overrides the record's path. Throws ConfigError
// (located at the file) when `partial` is not a tcpmsim record (no tcpmsim_version or config
// attribute, no /time) or already has a status, and
// std::runtime_error when the record cannot be written or would replace an existing file.
RecoveredRecord recover_partial_record(const std::string& partial, const std::string& output = "");

}  // namespace tcpmsim
