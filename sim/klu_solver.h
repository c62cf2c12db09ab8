#pragma once

#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>
#include <sundials/sundials_nvector.h>

namespace tcpmsim {

// SUNDIALS' KLU solver for a matrix whose pattern is fixed for the whole run: AMD ordering on
// A + A^T (the patterns here are (nearly) structurally symmetric; for a packed bundle's thermal
// network it fills a fifth less than KLU's default COLAMD); the symbolic analysis kept across
// CVodeReInit, which would otherwise redo it at every breakpoint; and a refactorisation that
// fails in the kept pivot order (a zero pivot) analysed and factored afresh before the caller
// hears of it. Used for the Newton matrix (solver.linear_solver: klu) and for GMRES's
// preconditioner. Returns nullptr if SUNDIALS cannot create it.
SUNLinearSolver make_klu_solver(N_Vector like, SUNMatrix matrix, SUNContext sundials);

}  // namespace tcpmsim
