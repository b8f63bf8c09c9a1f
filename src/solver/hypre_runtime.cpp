#include "sinew/solver/hypre_runtime.hpp"

#include <HYPRE_utilities.h>
#include <mpi.h>

#include <cstdlib>

#include "sinew/core/error.hpp"

// Under AddressSanitizer (scripts/sanitize) OpenMPI's plugins must stay loaded until the leak
// check: what they allocate at start-up is suppressed by module name (scripts/lsan.supp), and an
// unloaded plugin has none. OpenMPI unloads the plugins it did not select during MPI_Init and the
// rest in MPI_Finalize, so a sanitizer build makes dlclose a no-op (below; the executable exports
// it, CMakeLists.txt) and runs the leak check before MPI_Finalize. Sinew's own leaks are still found.
#if defined(__SANITIZE_ADDRESS__)
#define SINEW_LEAK_CHECK_BEFORE_MPI_FINALIZE 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define SINEW_LEAK_CHECK_BEFORE_MPI_FINALIZE 1
#endif
#endif
#ifdef SINEW_LEAK_CHECK_BEFORE_MPI_FINALIZE
#include <sanitizer/lsan_interface.h>
#endif

#ifdef SINEW_LEAK_CHECK_BEFORE_MPI_FINALIZE
extern "C" int dlclose(void* /*handle*/) { return 0; }  // sanitizer builds only: see above
#endif

namespace sinew {
namespace {

std::mutex& hypre_mutex() {
  static std::mutex m;
  return m;
}

void finalize_at_exit() {
#ifdef SINEW_LEAK_CHECK_BEFORE_MPI_FINALIZE
  __lsan_do_leak_check();  // the one check of the process (later ones are skipped)
#endif
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
