#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "sim/random_stream.h"

namespace tcpmsim::sweep {

// The values of one sweep axis and how axes combine into runs: pure functions of their
// arguments (and of a seeded stream), so a sweep's runs are the same on every machine.

enum class Spacing { linear, logarithmic };

// `count` values from `from` to `to`, both included, equally spaced (logarithmic: equal ratios,
// from and to of one sign and non-zero). count = 1 gives `from`.
std::vector<double> spaced_values(double from, double to, int count, Spacing spacing);

// A Latin hypercube column: [from, to] (or its logarithm) cut into `count` equal strata, one
// value drawn uniformly in each, the strata in a random order. Columns drawn this way from
// independent streams and zipped form a Latin hypercube design: every axis has exactly one run
// in each of its strata.
std::vector<double> latin_hypercube_values(double from, double to, int count, Spacing spacing,
                                           RandomStream& stream);

// Seeded draws: uniform on [from, to) (logarithmic: log-uniform), or normal.
std::vector<double> uniform_values(double from, double to, int count, Spacing spacing,
                                   RandomStream& stream);
std::vector<double> normal_values(double mean, double standard_deviation, int count,
                                  RandomStream& stream);

// A group of axes that vary together (zipped): column k holds axis k's values, all of one
// length.
using AxisGroup = std::vector<std::vector<double>>;

// The most runs a sweep may make: each is a simulation, and every run's values are held in
// memory before the first starts.
inline constexpr double kMaxRuns = 1e6;

// "" when a grid over `groups` makes at most kMaxRuns runs, else the product of the groups'
// lengths and the limit ("the axes make 1000 x 1000 x 1000 = 1e+09 runs, over ..."). Computed
// without building a run. Throws std::invalid_argument if a group's columns differ in length.
std::string grid_size_problem(const std::vector<AxisGroup>& groups);

// The runs of a grid over groups: every combination of one row from each group, the last
// group varying fastest. Each run lists the values of every axis, groups in order. Throws
// std::invalid_argument if a group's columns differ in length, or (before allocating) when
// grid_size_problem says the grid is too large.
std::vector<std::vector<double>> grid_runs(const std::vector<AxisGroup>& groups);

}  // namespace tcpmsim::sweep
