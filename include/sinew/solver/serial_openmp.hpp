#pragma once
// Debian's CHOLMOD 3 (SuiteSparse 5) is built with OpenMP loops that ask for a fixed number of
// threads (its compile-time CHOLMOD_OMP_NUM_THREADS), whatever the machine or OMP_NUM_THREADS
// says. On a machine with few cores, or with oneTBB workers about, those threads spin against
// each other: one factorisation of 1,872 DOFs took 11.3 ms with them and 3.9 ms without, 33k
// DOFs 75 ms against 34 ms (docs/performance.md). While a SerialOpenMpScope lives, every
// OpenMP parallel region started from the calling thread runs on that thread alone
// (max-active-levels 0); the previous setting is restored when it ends.
namespace sinew {

class SerialOpenMpScope {
 public:
  SerialOpenMpScope();
  ~SerialOpenMpScope();
  SerialOpenMpScope(const SerialOpenMpScope&) = delete;
  SerialOpenMpScope& operator=(const SerialOpenMpScope&) = delete;

 private:
  int saved_;
};

// Threads an OpenMP parallel region started here would use (1 inside a SerialOpenMpScope).
int openmp_threads_for_new_region();

}  // namespace sinew
