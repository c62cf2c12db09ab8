#include "sweep/sweep_design.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "sim/value_check.h"

namespace tcpmsim::sweep {
namespace {

// Maps u in [0, 1] onto [from, to], linearly or in log space.
double between(double from, double to, double u, Spacing spacing) {
  if (spacing == Spacing::linear) return from + (to - from) * u;
  return from * std::pow(to / from, u);
}

std::size_t row_count(const AxisGroup& group) {
  if (group.empty()) return 1;
  const std::size_t rows = group.front().size();
  for (const auto& column : group) {
    if (column.size() != rows)
      throw std::invalid_argument("the axes of a zipped group differ in length");
  }
  return rows;
}

}  // namespace

std::vector<double> spaced_values(double from, double to, int count, Spacing spacing) {
  std::vector<double> values;
  for (int k = 0; k < count; ++k) {
    // The ends exactly as given, not as rounding of the formula leaves them.
    if (k == 0)
      values.push_back(from);
    else if (k == count - 1)
      values.push_back(to);
    else
      values.push_back(between(from, to, static_cast<double>(k) / (count - 1), spacing));
  }
  return values;
}

std::vector<double> latin_hypercube_values(double from, double to, int count, Spacing spacing,
                                           RandomStream& stream) {
  std::vector<int> strata(static_cast<std::size_t>(count));
  std::iota(strata.begin(), strata.end(), 0);
  // Fisher-Yates on our own stream: std::shuffle's algorithm is not specified by the standard.
  for (int k = count - 1; k > 0; --k) {
    const auto pick = static_cast<int>(stream.uniform() * (k + 1));
    std::swap(strata[static_cast<std::size_t>(k)], strata[static_cast<std::size_t>(pick)]);
  }
  std::vector<double> values;
  for (int stratum : strata) {
    const double u = (stratum + stream.uniform()) / count;
    values.push_back(between(from, to, u, spacing));
  }
  return values;
}

std::vector<double> uniform_values(double from, double to, int count, Spacing spacing,
                                   RandomStream& stream) {
  std::vector<double> values;
  for (int k = 0; k < count; ++k) values.push_back(between(from, to, stream.uniform(), spacing));
  return values;
}

std::vector<double> normal_values(double mean, double standard_deviation, int count,
                                  RandomStream& stream) {
  std::vector<double> values;
  for (int k = 0; k < count; ++k) values.push_back(mean + standard_deviation * stream.normal());
  return values;
}

std::string grid_size_problem(const std::vector<AxisGroup>& groups) {
  double runs = 1.0;  // a double: a product of counts under a million each cannot overflow it
  std::string factors;
  for (const auto& group : groups) {
    const auto rows = row_count(group);
    runs *= static_cast<double>(rows);
    factors += (factors.empty() ? "" : " x ") + std::to_string(rows);
  }
  if (runs <= kMaxRuns) return "";
  return "the axes make " + factors + " = " + number_text(runs) + " runs, over the limit of " +
         number_text(kMaxRuns) +
         " runs a sweep (each is a simulation, and every run's values are held in memory); "
         "give fewer values, zip axes (combine: zip), or split the sweep";
}

std::vector<std::vector<double>> grid_runs(const std::vector<AxisGroup>& groups) {
  if (const std::string problem = grid_size_problem(groups); !problem.empty())
    throw std::invalid_argument(problem);
  std::vector<std::size_t> rows;
  std::size_t total = 1;
  for (const auto& group : groups) {
    rows.push_back(row_count(group));
    total *= rows.back();
  }
  std::vector<std::vector<double>> runs;
  runs.reserve(total);
  for (std::size_t run = 0; run < total; ++run) {
    // The run's row in each group: a mixed-radix number, the last group least significant.
    std::vector<std::size_t> row(groups.size());
    std::size_t rest = run;
    for (std::size_t g = groups.size(); g-- > 0;) {
      row[g] = rest % rows[g];
      rest /= rows[g];
    }
    std::vector<double> values;
    for (std::size_t g = 0; g < groups.size(); ++g) {
      for (const auto& column : groups[g]) values.push_back(column[row[g]]);
    }
    runs.push_back(std::move(values));
  }
  return runs;
}

}  // namespace tcpmsim::sweep
