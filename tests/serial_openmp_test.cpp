// SerialOpenMpScope: OpenMP regions (CHOLMOD's) run on one thread inside it, as before outside.
#include <gtest/gtest.h>

#include "sinew/solver/serial_openmp.hpp"

namespace sinew {
namespace {

TEST(SerialOpenMpScope, SerialisesNewRegionsAndRestoresTheSetting) {
  const int before = openmp_threads_for_new_region();
  EXPECT_GE(before, 1);
  {
    const SerialOpenMpScope outer;
    EXPECT_EQ(openmp_threads_for_new_region(), 1);
    {
      const SerialOpenMpScope inner;
      EXPECT_EQ(openmp_threads_for_new_region(), 1);
    }
    EXPECT_EQ(openmp_threads_for_new_region(), 1);  // the inner scope restores the outer's setting
  }
  EXPECT_EQ(openmp_threads_for_new_region(), before);
}

}  // namespace
}  // namespace sinew
