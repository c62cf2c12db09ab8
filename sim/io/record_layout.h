#pragma once

#include <string>
#include <vector>

#include "sim/system.h"

namespace tcpmsim {

// One dataset of a record: a channel of one instance (1-D, time), or the same channel of every
// member of a MemberSet (2-D, time x member, in the set's member order).
struct RecordSeries {
  std::string group;  // "muscle", "left/maxwell_branch", "b" or "b/drive" for a member set's
  std::string name;   // "force"
  std::string unit;
  std::vector<int> signal_indices;   // one per column
  std::vector<std::string> members;  // empty for a 1-D series
};

// Every recorded channel, its series in order of first appearance. A member's channel
// "b/m003/drive.power" goes to the series "b/drive" / "power", column 3. Throws std::logic_error
// if the members of a set do not record the same channels, or a member's series would take
// the place of one of the set's own ("b/supply.voltage" against a member part "supply").
std::vector<RecordSeries> record_layout(const System& system);

// The prescribed signals under /inputs: an instance's as "<group>.<name>"; the same signal of
// every member of a set as one entry "<set>[/<part>].<name>" listing the members' slots.
struct InputEntry {
  std::string path;                  // "drive.power", "b/drive.power"
  std::vector<int> slots;            // one per member (one for an instance's own)
  std::vector<std::string> members;  // empty for an instance's own
};
std::vector<InputEntry> input_layout(const System& system);

}  // namespace tcpmsim
