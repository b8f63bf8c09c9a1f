// libFuzzer target: the Gmsh .msh volume mesh reader (versions 2.2 and 4.1, ASCII).
#include "support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  sinew::fuzz::fuzz_volume_mesh(data, size, ".msh");
  return 0;
}
