#include "sim/klu_solver.h"

#include <sunlinsol/sunlinsol_klu.h>

#include <stdexcept>

namespace tcpmsim {
namespace {

// KLU then refactors with the pivot order it has and, when its condition estimate says that
// order went bad, factors afresh by itself.
int initialize_keeping_klu_analysis(SUNLinearSolver solver) {
  if (SUNLinSol_KLUGetSymbolic(solver) != nullptr) return SUNLS_SUCCESS;
  return SUNLinSolInitialize_KLU(solver);
}

int setup_repivoting_on_failure(SUNLinearSolver solver, SUNMatrix matrix) {
  const int flag = SUNLinSolSetup_KLU(solver, matrix);
  if (flag == SUNLS_SUCCESS) return flag;
  SUNLinSolInitialize_KLU(solver);
  return SUNLinSolSetup_KLU(solver, matrix);
}

}  // namespace

SUNLinearSolver make_klu_solver(N_Vector like, SUNMatrix matrix, SUNContext sundials) {
  SUNLinearSolver solver = SUNLinSol_KLU(like, matrix, sundials);
  if (!solver) return nullptr;
  if (SUNLinSol_KLUSetOrdering(solver, 0) != SUNLS_SUCCESS) {
    SUNLinSolFree(solver);
    throw std::runtime_error("could not set KLU's ordering");
  }
  solver->ops->initialize = initialize_keeping_klu_analysis;
  solver->ops->setup = setup_repivoting_on_failure;
  return solver;
}

}  // namespace tcpmsim
