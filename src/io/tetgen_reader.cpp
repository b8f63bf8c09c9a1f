// TetGen .node/.ele pairs (https://wias-berlin.de/software/tetgen/fformats.html): a .node file
// "count 3 attributes markers" then "index x y z [attributes] [marker]" rows, and a .ele
// file "count 4|10 attributes" then "index n1 n2 n3 n4 [...] [attribute]" rows; '#' starts a
// comment. Indices start at 0 or 1, as the first .node row says. Ten-node tetrahedra keep
// their four corners.
#include <fmt/format.h>
#include <string>
#include <vector>

#include "sinew/core/error.hpp"
#include "sinew/io/mesh_reader.hpp"
#include "sinew/io/text_scanner.hpp"

namespace sinew {
namespace {

std::int64_t read_count(TextScanner& in, std::string_view what, std::int64_t lo, std::int64_t hi) {
  return in.next_count(what, 0, lo, hi);
}

}  // namespace

VolumeMesh read_tetgen_mesh(const std::filesystem::path& path) {
  std::filesystem::path node_path = path, ele_path = path;
  node_path.replace_extension(".node");
  ele_path.replace_extension(".ele");
  VolumeMesh mesh;
  mesh.kind = ElementKind::Tet4;
  std::int64_t first_index = 0;
  {
    const std::string text = read_text_file(node_path);
    TextScanner in(text, node_path.string(), '#');
    const std::int64_t n = read_count(in, "the point count", 1, std::int64_t{1} << 31);
    read_count(in, "the dimension", 3, 3);
    const std::int64_t attributes = read_count(in, "the attribute count", 0, 1 << 20);
    const std::int64_t markers = read_count(in, "the boundary-marker flag", 0, 1);
    in.check_count_fits("the point count", n, 4 + attributes + markers);  // before sizing by it
    mesh.vertices.resize(n, 3);
    for (std::int64_t v = 0; v < n; ++v) {
      const std::int64_t index = in.next_integer("a point index");
      if (v == 0) {
        if (index != 0 && index != 1) in.fail(fmt::format("the first point index must be 0 or 1, got {}", index));
        first_index = index;
      } else if (index != first_index + v) {
        in.fail(fmt::format("point {} has index {} (points must be numbered consecutively)", first_index + v, index));
      }
      for (int i = 0; i < 3; ++i) mesh.vertices(v, i) = in.next_double("a point coordinate");
      for (std::int64_t a = 0; a < attributes + markers; ++a) in.next_double("a point attribute or marker");
    }
    if (!in.at_end()) {
      in.next("");
      in.fail(fmt::format("unexpected data after the {} points", n));
    }
  }
  const std::string text = read_text_file(ele_path);
  TextScanner in(text, ele_path.string(), '#');
  const std::int64_t n = read_count(in, "the tetrahedron count", 1, std::int64_t{1} << 31);
  const std::int64_t corners = in.next_integer("the nodes per tetrahedron");
  if (corners != 4 && corners != 10) in.fail(fmt::format("nodes per tetrahedron must be 4 or 10, got {}", corners));
  const std::int64_t attributes = read_count(in, "the attribute count", 0, 1 << 20);
  in.check_count_fits("the tetrahedron count", n, 1 + corners + attributes);  // before sizing by it
  mesh.elements.resize(n, 4);
  for (std::int64_t e = 0; e < n; ++e) {
    const std::int64_t index = in.next_integer("a tetrahedron index");
    if (index != first_index + e)
      in.fail(fmt::format("tetrahedron {} has index {} (tetrahedra must be numbered consecutively from the .node "
                          "file's first index, {})",
                          first_index + e, index, first_index));
    for (std::int64_t a = 0; a < corners; ++a) {
      const std::int64_t v = in.next_integer("a tetrahedron node") - first_index;
      if (v < 0 || v >= mesh.num_vertices())
        in.fail(fmt::format("tetrahedron {} refers to point {}, which {} does not define", index, v + first_index,
                            node_path.filename().string()));
      if (a < 4) mesh.elements(e, a) = static_cast<int>(v);
    }
    for (std::int64_t a = 0; a < attributes; ++a) in.next_double("a tetrahedron attribute");
  }
  if (!in.at_end()) {
    in.next("");
    in.fail(fmt::format("unexpected data after the {} tetrahedra", n));
  }
  return mesh;
}

}  // namespace sinew
