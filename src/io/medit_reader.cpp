// MEDIT ASCII .mesh (INRIA, P. Frey's format as read by Medit, MMG, TetGen): keyword sections
// each followed by a count and that many records; indices are 1-based and every record ends
// with an integer reference (a region or boundary label), which Sinew does not use.
//
// Node order: a MEDIT hexahedron lists one face (1 2 3 4, going round it) and then the
// opposite face with node 4+k above node k; a tetrahedron lists its four corners with the
// fourth on the side the right-hand normal of (1 2 3) points to. These are the VTK_HEXAHEDRON
// and VTK_TETRA orders, so the nodes are taken as they are (meshio and other converters also
// map these sections to VTK cells without permutation). A file whose elements have the
// opposite handedness reads as inverted elements and is rejected by validation.
#include <cctype>
#include <fmt/format.h>
#include <limits>
#include <string>
#include <vector>

#include "sinew/core/error.hpp"
#include "sinew/io/mesh_reader.hpp"
#include "sinew/io/text_scanner.hpp"

namespace sinew {
namespace {

bool keyword_is(std::string_view token, std::string_view keyword) {
  if (token.size() != keyword.size()) return false;
  for (std::size_t i = 0; i < token.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(token[i])) != std::tolower(static_cast<unsigned char>(keyword[i])))
      return false;
  return true;
}

// Sections describing boundary or geometry annotations: name, integers per record, reals
// per record. They are read (so the file is checked) and dropped.
struct SkippedSection {
  const char* name;
  int integers;
  int reals;
};
constexpr SkippedSection kSkipped[] = {
    {"Edges", 3, 0},          {"Triangles", 4, 0},         {"Quadrilaterals", 5, 0},
    {"Corners", 1, 0},        {"RequiredVertices", 1, 0},  {"Ridges", 1, 0},
    {"RequiredEdges", 1, 0},  {"RequiredTriangles", 1, 0}, {"RequiredQuadrilaterals", 1, 0},
    {"Normals", 0, 3},        {"NormalAtVertices", 2, 0},  {"Tangents", 0, 3},
    {"TangentAtVertices", 2, 0},
};
constexpr const char* kUnsupportedElements[] = {"Prisms", "Pyramids", "TetrahedraP2", "HexahedraQ2",
                                                "Pentahedra"};

// Messages name the item only as a kind ("a vertex coordinate"): the line number locates it,
// and formatting a description per token would dominate the reading time.
// `tokens_each`: the numbers per entry, so the count is checked against the rest of the file
// before anything is sized by it.
std::int64_t read_count(TextScanner& in, std::string_view section, std::int64_t tokens_each) {
  const std::int64_t n = in.next_integer("a section count");
  if (n < 0 || n > std::numeric_limits<int>::max()) {
    in.fail(fmt::format("{} count {} is out of range", section, n));
  }
  in.check_count_fits(fmt::format("the {} count", section), n, tokens_each);
  return n;
}

}  // namespace

VolumeMesh read_medit_mesh(const std::filesystem::path& path) {
  const std::string text = read_text_file(path);
  TextScanner in(text, path.string(), '#');
  VolumeMesh mesh;
  bool have_vertices = false, have_dimension = false;
  std::int64_t num_hex = 0, num_tet = 0;
  std::vector<int> hexes, tets;  // flat node lists, 0-based

  while (!in.at_end()) {
    const std::string_view keyword = in.next("a section keyword");
    if (keyword_is(keyword, "End")) break;
    if (keyword_is(keyword, "MeshVersionFormatted")) {
      const std::int64_t version = in.next_integer("the mesh version");
      if (version < 0 || version > 4) in.fail(fmt::format("unknown MeshVersionFormatted {}", version));
    } else if (keyword_is(keyword, "Dimension")) {
      const std::int64_t dim = in.next_integer("the dimension");
      if (dim != 3) in.fail(fmt::format("Dimension {} is not supported; volume meshes need 3", dim));
      have_dimension = true;
    } else if (keyword_is(keyword, "Vertices")) {
      if (have_vertices) in.fail("a second Vertices section");
      if (!have_dimension) in.fail("Vertices before Dimension 3");
      const std::int64_t n = read_count(in, "vertices", 4);
      mesh.vertices.resize(static_cast<Eigen::Index>(n), 3);
      for (std::int64_t v = 0; v < n; ++v) {
        for (int i = 0; i < 3; ++i) {
          mesh.vertices(static_cast<Eigen::Index>(v), i) = in.next_double("a vertex coordinate");
        }
        in.next_integer("a vertex reference");
      }
      have_vertices = true;
    } else if (keyword_is(keyword, "Hexahedra") || keyword_is(keyword, "Hexaedra") ||
               keyword_is(keyword, "Tetrahedra")) {
      const bool hex = !keyword_is(keyword, "Tetrahedra");
      const std::string section = hex ? "hexahedra" : "tetrahedra";
      if (!have_vertices) in.fail(fmt::format("{} before Vertices", keyword));
      const int nodes = hex ? 8 : 4;
      const std::int64_t n = read_count(in, section, nodes + 1);
      auto& list = hex ? hexes : tets;
      list.reserve(list.size() + static_cast<std::size_t>(n * nodes));
      for (std::int64_t e = 0; e < n; ++e) {
        for (int a = 0; a < nodes; ++a) {
          const std::int64_t v = in.next_integer("an element node");
          if (v < 1 || v > mesh.vertices.rows()) {
            in.fail(fmt::format("{} {} refers to vertex {}; indices run from 1 to {}",
                                hex ? "hexahedron" : "tetrahedron", e + 1, v,
                                mesh.vertices.rows()));
          }
          list.push_back(static_cast<int>(v - 1));  // 1-based
        }
        in.next_integer("an element reference");
      }
      (hex ? num_hex : num_tet) += n;
    } else {
      bool skipped = false;
      for (const auto& s : kSkipped) {
        if (!keyword_is(keyword, s.name)) continue;
        const std::int64_t n = read_count(in, s.name, s.integers + s.reals);
        for (std::int64_t r = 0; r < n; ++r) {
          for (int i = 0; i < s.integers; ++i) in.next_integer("an integer entry");
          for (int i = 0; i < s.reals; ++i) in.next_double("a real entry");
        }
        skipped = true;
        break;
      }
      if (skipped) continue;
      for (const char* name : kUnsupportedElements) {
        if (keyword_is(keyword, name)) {
          in.fail(fmt::format("{} are not supported; Sinew reads hexahedra or tetrahedra", name));
        }
      }
      in.fail(fmt::format("unknown MEDIT keyword '{}'", keyword));
    }
  }

  if (!have_vertices) throw Error("no Vertices section", path.string());
  if (num_hex > 0 && num_tet > 0) {
    throw Error(fmt::format("the file has {} hexahedra and {} tetrahedra; meshes mixing the two are "
                            "not supported",
                            num_hex, num_tet),
                path.string());
  }
  if (num_hex == 0 && num_tet == 0) throw Error("no Hexahedra or Tetrahedra", path.string());
  mesh.kind = num_hex > 0 ? ElementKind::Hex8 : ElementKind::Tet4;
  const auto& list = num_hex > 0 ? hexes : tets;
  const int nodes = nodes_per_element(mesh.kind);
  const auto ne = static_cast<Eigen::Index>(list.size()) / nodes;
  mesh.elements.resize(ne, nodes);
  for (Eigen::Index e = 0; e < ne; ++e)
    for (int a = 0; a < nodes; ++a) mesh.elements(e, a) = list[static_cast<std::size_t>(e * nodes + a)];
  return mesh;
}

}  // namespace sinew
