#pragma once

#include <cstdint>
#include <random>
#include <string_view>

namespace tcpmsim {

// A seeded stream of uniform numbers that is identical on every platform: std::mt19937_64 is
// fully specified by the standard, the conversions to [0, 1) below are ours (the standard
// distributions are not).
class RandomStream {
 public:
  // Streams for different `purpose`s (e.g. the config key of a signal) are independent.
  RandomStream(std::uint64_t seed, std::string_view purpose);
  double uniform();  // [0, 1)
  double uniform(double low, double high);
  bool chance(double probability);
  double normal();  // standard normal deviate (Box-Muller on this stream's uniforms)

 private:
  std::mt19937_64 engine_;
};

}  // namespace tcpmsim
