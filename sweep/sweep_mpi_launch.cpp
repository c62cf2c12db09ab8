#include <cstdlib>
#include <string>

#include "sim/config/config_error.h"
#include "sweep/sweep_mpi.h"

namespace tcpmsim::sweep {
namespace {

// The rank variables of Open MPI, MPICH/Hydra (PMI) and PMIx launchers (srun with PMIx sets
// PMIX_RANK; a plain srun task is not an MPI rank and runs the whole sweep).
constexpr const char* kRankVariables[] = {"OMPI_COMM_WORLD_RANK", "PMI_RANK", "PMIX_RANK"};

}  // namespace

bool launched_by_mpi() {
  return std::getenv("OMPI_COMM_WORLD_SIZE") != nullptr || std::getenv("PMI_SIZE") != nullptr ||
         std::getenv("PMIX_RANK") != nullptr;
}

int launched_rank() {
  for (const char* variable : kRankVariables) {
    if (const char* value = std::getenv(variable)) return std::atoi(value);
  }
  return 0;
}

#ifndef TCPMSIM_WITH_MPI
bool mpi_available() {
  return false;
}

SweepOutcome run_sweep_mpi(const SweepSpec&, const SweepOptions&, std::shared_ptr<const UnitSystem>,
                           const SweepProgress&) {
  throw UsageError("this tcpmsim was built without MPI (install libopenmpi-dev and rebuild)");
}
#endif

}  // namespace tcpmsim::sweep
