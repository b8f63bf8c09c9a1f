// libFuzzer target: the scene reader (load_scene: JSON parsing, then every section's checks).
// Files the scene names (meshes, surfaces, rigs) resolve next to the input, where there are
// none, so those paths end in "not found" errors; building the mesh is left out because a
// valid scene may ask for up to 50 million cells.
#include "support.hpp"
#include "sinew/model/scene.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = sinew::fuzz::write_input(data, size, "scene.json");
  sinew::fuzz::expect_clean([&] { sinew::load_scene(path); }, path);
  return 0;
}
