// libFuzzer target: the .ply triangle surface reader (Sinew's checks, then CGAL's reader).
#include "support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  sinew::fuzz::fuzz_surface(data, size, ".ply");
  return 0;
}
