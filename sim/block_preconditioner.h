#pragma once

#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>
#include <sundials/sundials_nvector.h>

#include <vector>

#include "sim/sparsity.h"

namespace tcpmsim {

// The preconditioner of CVODE's Krylov (GMRES) Newton solves: P = I - gamma J_B, where J_B is
// the Jacobian without the entries between members (JacobianEntries::within_members), factored
// by KLU. Within members P is the Newton matrix itself, so GMRES only has the couplings between
// members to resolve (a bundle's contact conduction, a shared supply), and the factorisation
// stays as sparse as the members are: its cost grows linearly with their number, where the
// whole matrix's LU fills like a 2-D grid's.
class BlockPreconditioner {
 public:
  // `whole` is the Jacobian's pattern, `blocks` the part of it within members (a subset).
  BlockPreconditioner(const SparsityPattern& whole, const SparsityPattern& blocks, N_Vector like,
                      SUNContext sundials);
  ~BlockPreconditioner();
  BlockPreconditioner(const BlockPreconditioner&) = delete;
  BlockPreconditioner& operator=(const BlockPreconditioner&) = delete;

  // Forms I - gamma J_B from the whole Jacobian (CSC in `whole`'s layout) and factors it.
  // Returns 0, or a positive (recoverable) value if the factorisation fails.
  int setup(SUNMatrix jacobian, double gamma);
  // z = P^-1 r. Returns 0 or a positive value.
  int solve(N_Vector r, N_Vector z);

 private:
  SUNMatrix matrix_ = nullptr;
  SUNLinearSolver solver_ = nullptr;
  std::vector<sunindextype> source_entry_;  // per entry of P: its entry in the whole Jacobian
  std::vector<char> diagonal_;              // per entry of P: on the diagonal
};

}  // namespace tcpmsim
