#include "sinew/solver/serial_openmp.hpp"

#include <omp.h>

namespace sinew {

SerialOpenMpScope::SerialOpenMpScope() : saved_(omp_get_max_active_levels()) { omp_set_max_active_levels(0); }

SerialOpenMpScope::~SerialOpenMpScope() { omp_set_max_active_levels(saved_); }

int openmp_threads_for_new_region() {
  if (omp_get_active_level() >= omp_get_max_active_levels()) return 1;
  return omp_get_max_threads();
}

}  // namespace sinew
