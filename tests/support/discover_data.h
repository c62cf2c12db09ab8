#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "identification/discovery.h"

// The data and requests of discover's specifications (tests/test_discover*.cpp).
namespace tcpmsim::testing {

// A measurement of configs/discover/ch7_base.yaml with `hidden` overrides (the effect it holds),
// read by the chapter-7 bench (load cell 0.5 mN resolution and 1 mN noise, L* jitter and
// spikes), written as a CSV; its path. The protocol is cut to `duration`: 200 s of multisines to
// identify, the rest random steps to validate, to keep the suite quick (the whole protocol is
// scripts/discover_matrix.py's). `bench_seed` is the bench's seed: the matrix's case seed.
std::string discover_measurement(const std::string& name, std::vector<std::string> hidden,
                                 const std::string& duration = "300 s",
                                 std::uint64_t bench_seed = 1);

// A request for such data: the simplest member of each family (the nesting test tries them
// all), two multistart points per fit, validation from 200 s, to keep the suite quick.
fit::DiscoverRequest discover_request(const std::string& data, std::vector<std::string> effects);

// The short discover: a Dahl element (50 N/m, 6 mN) hidden in 120 s of data, 80 s to identify and
// 40 s to validate, the hysteresis family alone, one start: every stage of a discover at the
// least cost (what the sanitizer tree runs whole).
fit::DiscoverRequest short_hysteresis_request();

// The candidates' effect names, in the catalogue's order (a family once per member).
std::vector<std::string> candidate_names(const fit::Candidates& candidates);

}  // namespace tcpmsim::testing
