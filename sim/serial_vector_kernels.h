#pragma once

#include <sundials/sundials_nvector.h>

namespace tcpmsim {

// Debian 12 ships SUNDIALS 6.4.1 compiled without optimisation (its N_VWSqrSumLocal_Serial
// keeps every variable on the stack: about 21 instructions per element where 3 suffice), and
// CVODE spends most of a step in these vector kernels. SUNDIALS lets a program provide its own
// vector operations; CVODE clones every internal vector from the one it is given, so
// installing these on the state vector reaches them all.
//
// The replacements compute exactly what the serial ones do, special cases included
// (a == b gives c (x + y), a == -b gives c (x - y); the others are arithmetically identical
// to a x + b y), in the same order of operations, so results are bit-identical; a test
// checks every kernel against Debian's.
void install_optimised_serial_kernels(N_Vector serial_vector);

}  // namespace tcpmsim
