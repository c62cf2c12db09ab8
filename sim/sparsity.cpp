#include "sim/sparsity.h"

#include <algorithm>

namespace tcpmsim {

int SparsityPattern::non_zeros() const {
  int count = 0;
  for (const auto& rows : rows_of_column) count += static_cast<int>(rows.size());
  return count;
}

namespace {
// Largest (column - row) over the pattern: the upper half-bandwidth; with rows and columns
// swapped in the sign, the lower one.
int largest_offset(const SparsityPattern& pattern, int sign) {
  int largest = 0;
  for (int column = 0; column < pattern.size; ++column) {
    for (int row : pattern.rows_of_column[static_cast<std::size_t>(column)]) {
      largest = std::max(largest, sign * (column - row));
    }
  }
  return largest;
}
}  // namespace

int SparsityPattern::upper_bandwidth() const {
  return largest_offset(*this, +1);
}

int SparsityPattern::lower_bandwidth() const {
  return largest_offset(*this, -1);
}

std::vector<std::vector<int>> SparsityPattern::column_groups() const {
  // Greedy colouring in column order; good enough for the chain and block structures here.
  std::vector<std::vector<int>> groups;
  std::vector<std::vector<char>> rows_used;
  // Rows may extend past the square part (pseudo-rows the Integrator adds for its chain rule).
  int rows_count = size;
  for (const auto& rows : rows_of_column)
    if (!rows.empty()) rows_count = std::max(rows_count, rows.back() + 1);
  for (int column = 0; column < size; ++column) {
    const auto& rows = rows_of_column[static_cast<std::size_t>(column)];
    std::size_t group = 0;
    for (; group < groups.size(); ++group) {
      const auto& used = rows_used[group];
      const bool clash =
          std::any_of(rows.begin(), rows.end(), [&](int row) { return used[row] != 0; });
      if (!clash) break;
    }
    if (group == groups.size()) {
      groups.emplace_back();
      rows_used.emplace_back(static_cast<std::size_t>(rows_count), 0);
    }
    groups[group].push_back(column);
    for (int row : rows) rows_used[group][static_cast<std::size_t>(row)] = 1;
  }
  return groups;
}

}  // namespace tcpmsim
