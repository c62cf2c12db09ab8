#pragma once

#include <H5Cpp.h>

#include <string>
#include <vector>

#include "sim/signal.h"

namespace tcpmsim {

// A prescribed signal as a record's /inputs describes it (written by the record writer from
// Signal::describe): its path ("drive.power", "b/drive.power"), unit, description and, for a
// member set's signal written once, the members.
struct RecordedInput {
  std::string path;
  std::string unit;
  SignalDescription description;
  std::vector<std::string> members;
};

// Every input under the file's /inputs (none if it has no /inputs), read back into the
// descriptions the writer wrote: the type attribute, the numeric attributes as parameters, the
// datasets as arrays and the subgroups as parts, in their natural order (segment2 before
// segment10).
std::vector<RecordedInput> read_record_inputs(const H5::H5File& file);
SignalDescription read_signal_description(const H5::Group& group);

}  // namespace tcpmsim
