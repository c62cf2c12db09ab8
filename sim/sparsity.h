#pragma once

#include <vector>

namespace tcpmsim {

// Structural non-zeros of a square matrix, stored by column (the layout KLU wants).
struct SparsityPattern {
  int size = 0;
  std::vector<std::vector<int>> rows_of_column;  // sorted, unique

  int non_zeros() const;
  // Half-bandwidths of the pattern: entries (i, j) with j - i <= upper and i - j <= lower.
  int upper_bandwidth() const;
  int lower_bandwidth() const;
  // Groups of structurally orthogonal columns: columns in one group share no row, so one
  // finite-difference evaluation recovers all of them (Curtis-Powell-Reid).
  std::vector<std::vector<int>> column_groups() const;
};

}  // namespace tcpmsim
