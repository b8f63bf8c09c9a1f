// libFuzzer target: the MEDIT .mesh volume mesh reader.
#include "support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  sinew::fuzz::fuzz_volume_mesh(data, size, ".mesh");
  return 0;
}
