#include "sim/io/record_layout.h"

#include <map>
#include <stdexcept>
#include <unordered_map>
#include <utility>

namespace tcpmsim {

namespace {

struct MemberPlace {
  std::size_t set;
  std::size_t column;
};

// "b/m003" for every member of every set.
std::unordered_map<std::string, MemberPlace> member_places(const System& system) {
  std::unordered_map<std::string, MemberPlace> places;
  const auto& sets = system.member_sets();
  for (std::size_t s = 0; s < sets.size(); ++s) {
    for (std::size_t m = 0; m < sets[s].members.size(); ++m)
      places[sets[s].name + "/" + sets[s].members[m]] = {s, m};
  }
  return places;
}

// The instance a group belongs to with its first part: "b/m003" of "b/m003/drive".
std::string first_two_levels(const std::string& group) {
  const auto first = group.find('/');
  if (first == std::string::npos) return group;
  return group.substr(0, group.find('/', first + 1));
}

// Where a group of a member lands: the set's name with the part ("b/drive"), or nullptr.
struct MemberGroup {
  const MemberSet* set = nullptr;
  std::size_t column = 0;
  std::string group;
};
MemberGroup member_group(const System& system,
                         const std::unordered_map<std::string, MemberPlace>& places,
                         const std::string& group) {
  const std::string member = first_two_levels(group);
  const auto place = places.find(member);
  if (place == places.end()) return {};
  const MemberSet& set = system.member_sets()[place->second.set];
  return {&set, place->second.column, set.name + group.substr(member.size())};
}

}  // namespace

std::vector<InputEntry> input_layout(const System& system) {
  const auto places = member_places(system);
  std::vector<InputEntry> layout;
  std::map<std::string, std::size_t> by_path;
  const auto& slots = system.signal_slots();
  for (std::size_t s = 0; s < slots.size(); ++s) {
    const MemberGroup member = member_group(system, places, slots[s].group);
    if (!member.set) {
      layout.push_back({slots[s].group + "." + slots[s].name, {static_cast<int>(s)}, {}});
      continue;
    }
    const std::string path = member.group + "." + slots[s].name;
    auto [entry, created] = by_path.emplace(path, layout.size());
    if (created)
      layout.push_back(
          {path, std::vector<int>(member.set->members.size(), -1), member.set->members});
    layout[entry->second].slots[member.column] = static_cast<int>(s);
  }
  for (const auto& entry : layout) {
    for (const int slot : entry.slots)
      if (slot < 0) throw std::logic_error("not every member applies the signal " + entry.path);
  }
  return layout;
}

std::vector<RecordSeries> record_layout(const System& system) {
  const auto places = member_places(system);
  std::vector<RecordSeries> layout;
  std::map<std::pair<std::string, std::string>, std::size_t> by_path;  // (group, name) -> series
  for (const auto& channel : system.channels()) {
    if (!channel.recorded) continue;
    const MemberGroup member = member_group(system, places, channel.group);
    if (!member.set) {
      if (!by_path.emplace(std::pair{channel.group, channel.name}, layout.size()).second)
        throw std::logic_error("two series are recorded as " + channel.group + "/" + channel.name);
      layout.push_back({channel.group, channel.name, channel.unit, {channel.signal_index}, {}});
      continue;
    }
    const MemberSet& set = *member.set;
    const std::pair<std::string, std::string> path{member.group, channel.name};
    auto [entry, created] = by_path.emplace(path, layout.size());
    if (created) {
      layout.push_back({path.first, channel.name, channel.unit,
                        std::vector<int>(set.members.size(), -1), set.members});
    }
    RecordSeries& series = layout[entry->second];
    if (series.members.empty())
      throw std::logic_error("a member's series " + path.first + "/" + path.second +
                             " takes the place of one of " + set.name + "'s own");
    series.signal_indices[member.column] = channel.signal_index;
  }
  for (const auto& series : layout) {
    for (std::size_t k = 0; k < series.members.size(); ++k) {
      if (series.signal_indices[k] < 0)
        throw std::logic_error("member " + series.members[k] + " of " + series.group +
                               " does not record " + series.name + " as the others do");
    }
  }
  return layout;
}

}  // namespace tcpmsim
