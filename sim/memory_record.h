#pragma once

#include <map>
#include <span>
#include <string>
#include <vector>

#include "sim/integrator.h"
#include "sim/system.h"

namespace tcpmsim {

// Every output of a run, kept in memory by channel ("group/name"): for analyses that run
// scenarios themselves rather than reading an HDF5 record.
class MemoryRecord final : public OutputSink {
 public:
  explicit MemoryRecord(const System& system);
  // Moves keep the channels' storage (a map's nodes move with it); a copy would record into the
  // original's, so there is none.
  MemoryRecord(MemoryRecord&&) = default;
  MemoryRecord& operator=(MemoryRecord&&) = default;
  MemoryRecord(const MemoryRecord&) = delete;
  MemoryRecord& operator=(const MemoryRecord&) = delete;
  void record(double time, std::span<const double> signals) override;

  std::vector<double> time;
  std::map<std::string, std::vector<double>> channels;
  // Throws std::out_of_range naming the channel if it is not recorded.
  const std::vector<double>& operator[](const std::string& channel) const;

 private:
  std::vector<std::pair<std::vector<double>*, int>> layout_;  // each channel's storage, signal
};

}  // namespace tcpmsim
