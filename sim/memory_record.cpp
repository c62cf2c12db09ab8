#include "sim/memory_record.h"

#include <stdexcept>

namespace tcpmsim {

MemoryRecord::MemoryRecord(const System& system) {
  for (const auto& channel : system.channels()) {
    if (!channel.recorded) continue;
    layout_.emplace_back(&channels[channel.group + "/" + channel.name], channel.signal_index);
  }
}

void MemoryRecord::record(double t, std::span<const double> signals) {
  time.push_back(t);
  for (const auto& [values, index] : layout_)
    values->push_back(signals[static_cast<std::size_t>(index)]);
}

const std::vector<double>& MemoryRecord::operator[](const std::string& channel) const {
  const auto found = channels.find(channel);
  if (found == channels.end()) throw std::out_of_range("no channel " + channel + " in the record");
  return found->second;
}

}  // namespace tcpmsim
