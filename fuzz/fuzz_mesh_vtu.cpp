// libFuzzer target: the .vtu volume mesh reader (read_volume_mesh on a .vtu file).
#include "support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  sinew::fuzz::fuzz_volume_mesh(data, size, ".vtu");
  return 0;
}
