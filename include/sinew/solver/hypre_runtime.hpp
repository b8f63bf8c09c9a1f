#pragma once
// hypre as Sinew uses it: one process, no mpirun. Debian builds hypre with MPI, so MPI is
// initialised on first use (never at start-up, so runs that do not use hypre do not pay for it)
// and finalised at exit; hypre then works on MPI_COMM_SELF. hypre keeps global state (its error
// flag, its memory bookkeeping), so callers hold hypre_lock() around every hypre call.
#include <mutex>

namespace sinew {

// Initialises MPI (if nobody has) and hypre, once; a sinew::Error if MPI cannot start.
void ensure_hypre_initialized();

// Serialises the process's hypre calls.
std::unique_lock<std::mutex> hypre_lock();

// True once MPI has been finalised (at exit): hypre objects are then leaked, not destroyed.
bool hypre_finalized();

}  // namespace sinew
