#pragma once

#include <memory>

#include "sim/config/units.h"
#include "sweep/sweep_executor.h"
#include "sweep/sweep_spec.h"

namespace tcpmsim::sweep {

// Whether this process was started by an MPI launcher (mpirun, srun): its environment names a
// rank. Then `tcpmsim sweep` runs as one rank of the job.
bool launched_by_mpi();
// This process' rank as the launcher named it (0 without one): only rank 0 reports errors.
int launched_rank();

// Whether this build has MPI (the MPI part builds only when CMake finds an MPI).
bool mpi_available();

// The sweep on every rank of the MPI job (each on options.threads threads): a counter held by
// rank 0 and advanced by one-sided atomic fetch-and-add hands the runs out one at a time to
// whichever rank asks first. Every rank stores its runs in the shared parts directory (the
// output's directory must be on a file system every rank sees); rank 0 opens the store, merges
// the summary at the end and reports progress. Results do not depend on the rank count.
// Throws std::logic_error if the build has no MPI.
SweepOutcome run_sweep_mpi(const SweepSpec& spec, const SweepOptions& options,
                           std::shared_ptr<const UnitSystem> units,
                           const SweepProgress& progress = {});

}  // namespace tcpmsim::sweep
