#include "sinew/solver/hypre_runtime.hpp"

#include <HYPRE_utilities.h>
#include <mpi.h>

#include <cstdlib>

#include "sinew/core/error.hpp"

namespace sinew {
namespace {

std::mutex& hypre_mutex() {
  static std::mutex m;
  return m;
}

void finalize_at_exit() {
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (!finalized) MPI_Finalize();  // removes OpenMPI's session directory under /tmp
}

}  // namespace

void ensure_hypre_initialized() {
  static std::once_flag once;
  std::call_once(once, [] {
    int initialized = 0;
    MPI_Initialized(&initialized);
    if (!initialized) {
      // Started without mpirun: OpenMPI would otherwise fork a helper daemon for this lone
      // process (twice the start-up time). Other MPIs ignore the variable; a user's value wins.
      if (!std::getenv("OMPI_COMM_WORLD_SIZE")) setenv("OMPI_MCA_ess_singleton_isolated", "1", 0);
      int provided = 0;
      // Serialized: Sinew's threads call hypre one at a time (hypre_lock), not only the main one.
      if (MPI_Init_thread(nullptr, nullptr, MPI_THREAD_SERIALIZED, &provided) != MPI_SUCCESS)
        throw Error("MPI could not be initialised", "hypre");
      std::atexit(finalize_at_exit);
    }
    HYPRE_Init();
  });
}

std::unique_lock<std::mutex> hypre_lock() { return std::unique_lock<std::mutex>(hypre_mutex()); }

bool hypre_finalized() {
  int finalized = 0;
  MPI_Finalized(&finalized);
  return finalized != 0;
}

}  // namespace sinew
