// libFuzzer target: the rig file reader (load_rig).
#include "support.hpp"
#include "sinew/model/rig_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = sinew::fuzz::write_input(data, size, "rig.json");
  sinew::fuzz::expect_clean([&] { sinew::load_rig(path); }, path);
  return 0;
}
