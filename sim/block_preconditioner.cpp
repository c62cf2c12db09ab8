#include "sim/block_preconditioner.h"

#include "sim/klu_solver.h"

#include <sunmatrix/sunmatrix_sparse.h>

#include <algorithm>
#include <stdexcept>

namespace tcpmsim {

BlockPreconditioner::BlockPreconditioner(const SparsityPattern& whole,
                                         const SparsityPattern& blocks, N_Vector like,
                                         SUNContext sundials) {
  matrix_ = SUNSparseMatrix(blocks.size, blocks.size, blocks.non_zeros(), CSC_MAT, sundials);
  if (!matrix_) throw std::runtime_error("could not create the preconditioner's matrix");
  sunindextype* column_start = SUNSparseMatrix_IndexPointers(matrix_);
  sunindextype* row_index = SUNSparseMatrix_IndexValues(matrix_);
  sunindextype entry = 0;
  sunindextype whole_start = 0;
  for (int column = 0; column < blocks.size; ++column) {
    const auto& rows = whole.rows_of_column[static_cast<std::size_t>(column)];
    column_start[column] = entry;
    for (int row : blocks.rows_of_column[static_cast<std::size_t>(column)]) {
      const auto place = std::lower_bound(rows.begin(), rows.end(), row);
      if (place == rows.end() || *place != row)
        throw std::logic_error("the preconditioner's pattern is not part of the Jacobian's");
      row_index[entry++] = row;
      source_entry_.push_back(whole_start + (place - rows.begin()));
      diagonal_.push_back(row == column ? 1 : 0);
    }
    whole_start += static_cast<sunindextype>(rows.size());
  }
  column_start[blocks.size] = entry;
  solver_ = make_klu_solver(like, matrix_, sundials);
  if (!solver_) throw std::runtime_error("could not create the preconditioner's KLU solver");
}

BlockPreconditioner::~BlockPreconditioner() {
  if (solver_) SUNLinSolFree(solver_);
  if (matrix_) SUNMatDestroy(matrix_);
}

int BlockPreconditioner::setup(SUNMatrix jacobian, double gamma) {
  const double* source = SUNSparseMatrix_Data(jacobian);
  double* data = SUNSparseMatrix_Data(matrix_);
  for (std::size_t k = 0; k < source_entry_.size(); ++k)
    data[k] = (diagonal_[k] ? 1.0 : 0.0) - gamma * source[source_entry_[k]];
  return SUNLinSolSetup(solver_, matrix_) == SUNLS_SUCCESS ? 0 : 1;
}

int BlockPreconditioner::solve(N_Vector r, N_Vector z) {
  return SUNLinSolSolve(solver_, matrix_, z, r, 0.0) == SUNLS_SUCCESS ? 0 : 1;
}

}  // namespace tcpmsim
