#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "sim/config/units.h"
#include "sim/scenario.h"

namespace tcpmsim::fit {

// How a bench instrument reads one model output: the channel it writes, in which unit, with
// what resolution, noise and spikes (the Muscle Drive's L* has them).
struct Instrument {
  std::string channel;  // "force"
  std::string output;   // the model's "load.force"
  std::string unit;     // written in: "mN"
  std::string si_unit;  // the output's
  double noise = 0.0;   // standard deviation of added white normal noise [SI]
  // A correlated part beside it (a sensor's filter, a slow wander): first-order (AR(1)) noise
  // of standard deviation `correlated_noise` [SI] and correlation time tau [s],
  // e_i = phi e_(i-1) + sqrt(1 - phi^2) correlated_noise w_i, phi = exp(-dt / tau), drawn
  // from a stream of its own, so the white part is the same with it or without.
  double correlated_noise = 0.0;
  double correlation_time = 0.0;
  double resolution = 0.0;         // readings are multiples of it [SI]; 0: continuous
  double spike_probability = 0.0;  // per sample
  double spike_size = 0.0;         // a spike adds +-size [SI], its sign drawn
};

// A bench file, read:
//   seed: 1
//   channels:
//     - {channel: power, output: drive.power, unit: W}
//     - {channel: force, output: load.force, unit: mN, resolution: 0.5 mN, noise: 1 mN,
//        correlated_noise: {size: 0.5 mN, correlation_time: 0.5 s}}
//     - {channel: inductance_measure, output: muscle.inductance_measure, unit: "1",
//        noise: 0.002, spikes: {probability: 0.01, size: 0.05}}
// Channels are checked against the measured quantities and the scenario's outputs.
struct Bench {
  std::uint64_t seed = 1;
  std::vector<Instrument> instruments;
};
Bench load_bench(const std::string& file, const Scenario& scenario,
                 std::shared_ptr<const UnitSystem> units);

// The scenario run once and read by the bench's instruments at its output times: a CSV text
// with name[unit] headings (time in s), every value to 17 significant digits. Each instrument
// draws from its own seeded stream, so adding one does not change the others' noise.
std::string measure(const Scenario& scenario, const Bench& bench, const UnitSystem& units);

}  // namespace tcpmsim::fit
