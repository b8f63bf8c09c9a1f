// libFuzzer target: the TetGen .node/.ele reader. The input is the .node file, a line "---",
// then the .ele file (the seed corpus is built that way by scripts/fuzz).
#include <string>

#include "support.hpp"
#include "sinew/io/mesh_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string input(reinterpret_cast<const char*>(data), size);
  const std::size_t split = input.find("\n---\n");
  const std::string node = split == std::string::npos ? input : input.substr(0, split + 1);
  const std::string ele = split == std::string::npos ? std::string() : input.substr(split + 5);
  const auto node_path = sinew::fuzz::write_input(node, "input.node");
  const auto ele_path = sinew::fuzz::write_input(ele, "input.ele");
  // Either file may be the one named; both share the stem "input".
  sinew::fuzz::expect_clean([&] { sinew::read_volume_mesh(node_path); }, "input");
  return 0;
}
