// Tetrahedral mesh files: Gmsh .msh (ASCII 2.2 and 4.1) and TetGen .node/.ele, good and broken;
// inverted elements are rejected with their index unless reorientation is asked for.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include "io_test_support.hpp"
#include "sinew/element/mesh_validation.hpp"
#include "sinew/io/mesh_reader.hpp"
#include "sinew/element/reorient.hpp"

namespace sinew {
namespace {

using test::error_message;
using test::expect_contains;
using test::TempDir;

// Two tetrahedra sharing face (2 3 4), node tags 10..50; plus a boundary triangle and a point.
const char* kMsh2 = R"($MeshFormat
2.2 0 8
$EndMeshFormat
$PhysicalNames
1
3 1 "body"
$EndPhysicalNames
$Nodes
5
10 0 0 0
20 1 0 0
30 0 1 0
40 0 0 1
50 1 1 1
$EndNodes
$Elements
4
1 15 2 0 1 10
2 2 2 0 1 10 30 20
3 4 2 1 1 10 20 30 40
4 4 2 1 1 20 50 30 40
$EndElements
)";

const char* kMsh4 = R"($MeshFormat
4.1 0 8
$EndMeshFormat
$Entities
0 0 0 1
1 0 0 0 1 1 1 0 0
$EndEntities
$Nodes
2 5 1 5
3 1 0 3
1
2
3
0 0 0
1 0 0
0 1 0
3 1 0 2
4
5
0 0 1
1 1 1
$EndNodes
$Elements
2 3 1 3
2 1 2 1
1 1 3 2
3 1 4 2
2 1 2 3 4
3 2 5 3 4
$EndElements
)";

TEST(TetMeshReader, GmshVersions2And4) {
  TempDir dir;
  for (const char* text : {kMsh2, kMsh4}) {
    const VolumeMesh m = read_volume_mesh(dir.write("two.msh", text));
    EXPECT_EQ(m.kind, ElementKind::Tet4);
    ASSERT_EQ(m.num_vertices(), 5);
    ASSERT_EQ(m.num_elements(), 2);
    EXPECT_EQ(m.elements.row(0), Eigen::RowVector4i(0, 1, 2, 3));
    EXPECT_EQ(m.elements.row(1), Eigen::RowVector4i(1, 4, 2, 3));
    EXPECT_EQ(m.vertices.row(4), Eigen::RowVector3d(1, 1, 1));
  }
}

TEST(TetMeshReader, BrokenGmshFilesNameFileAndLine) {
  TempDir dir;
  const std::string good = kMsh2;
  auto message = [&](const std::string& name, const std::string& text) {
    const auto path = dir.write(name, text);
    return error_message([&] { read_volume_mesh(path); });
  };
  auto replaced = [&](const std::string& from, const std::string& to) {
    std::string s = good;
    s.replace(s.find(from), from.size(), to);
    return s;
  };
  expect_contains(message("cut.msh", good.substr(0, good.find("4 4 2 1 1"))), {"cut.msh:21", "end of file"});
  expect_contains(message("nan.msh", replaced("30 0 1 0", "30 0 nan 0")), {"nan.msh:12"});
  expect_contains(message("ref.msh", replaced("20 50 30 40", "20 60 30 40")), {"ref.msh:21", "node 60"});
  expect_contains(message("binary.msh", replaced("2.2 0 8", "2.2 1 8")), {"binary.msh:2", "binary"});
  expect_contains(message("version.msh", replaced("2.2 0 8", "3.0 0 8")), {"version.msh:2", "3.0"});
  // Swapping two nodes inverts element 1 (0-based, the second tetrahedron).
  const std::string inverted = replaced("20 50 30 40", "50 20 30 40");
  expect_contains(message("inverted.msh", inverted), {"inverted.msh", "element 1", "inverted"});
  const VolumeMesh fixed = read_volume_mesh(dir.write("inverted2.msh", inverted), {.reorient_inverted = true});
  EXPECT_EQ(fixed.num_elements(), 2);
  // Zero volume cannot be reoriented.
  const std::string flat = replaced("50 1 1 1", "50 0.5 0.5 0");
  expect_contains(error_message([&] { read_volume_mesh(dir.write("flat.msh", flat), {.reorient_inverted = true}); }),
                  {"flat.msh", "element 1", "degenerate"});
}

TEST(TetMeshReader, TetGenNodeEleBothBases) {
  TempDir dir;
  for (int base : {0, 1}) {
    const std::string stem = fmt::format("two{}", base);
    dir.write(stem + ".node", fmt::format("# points\n5 3 0 1\n{} 0 0 0 1\n{} 1 0 0 1\n{} 0 1 0 1\n{} 0 0 1 1\n{} 1 1 1 1\n",
                                          base, base + 1, base + 2, base + 3, base + 4));
    dir.write(stem + ".ele", fmt::format("2 4 1\n{} {} {} {} {} 7\n{} {} {} {} {} 7\n", base, base, base + 1, base + 2,
                                         base + 3, base + 1, base + 1, base + 4, base + 2, base + 3));
    for (const char* ext : {".ele", ".node"}) {
      const VolumeMesh m = read_volume_mesh(dir / (stem + ext));
      ASSERT_EQ(m.num_elements(), 2);
      EXPECT_EQ(m.elements.row(1), Eigen::RowVector4i(1, 4, 2, 3));
    }
  }
  dir.write("bad.node", "4 3 0 0\n0 0 0 0\n1 1 0 0\n2 0 1 0\n3 0 0 1\n");
  dir.write("bad.ele", "1 4 0\n0 0 1 2 4\n");
  expect_contains(error_message([&] { read_volume_mesh(dir / "bad.ele"); }), {"bad.ele:2", "point 4"});
  dir.write("cut.node", "4 3 0 0\n0 0 0 0\n1 1 0 0\n2 0 1 0\n");
  expect_contains(error_message([&] { read_volume_mesh(dir / "cut.node"); }), {"cut.node:5", "end of file"});
  dir.write("nan.node", "4 3 0 0\n0 0 0 0\n1 1 0 0\n2 0 NaN 0\n3 0 0 1\n");
  dir.write("nan.ele", "1 4 0\n0 0 1 2 3\n");
  expect_contains(error_message([&] { read_volume_mesh(dir / "nan.ele"); }), {"nan.node:4"});
  dir.write("inv.node", "4 3 0 0\n0 0 0 0\n1 1 0 0\n2 0 1 0\n3 0 0 1\n");
  dir.write("inv.ele", "1 4 0\n0 0 2 1 3\n");
  expect_contains(error_message([&] { read_volume_mesh(dir / "inv.ele"); }), {"inv.ele", "element 0", "inverted"});
  expect_contains(error_message([&] { read_volume_mesh(dir / "none.ele"); }), {"none.node"});
}

TEST(TetMeshReader, ReorientFlipsMirroredHexesAndTets) {
  VolumeMesh hex;
  hex.kind = ElementKind::Hex8;
  hex.vertices.resize(8, 3);
  hex.vertices << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1;
  hex.elements.resize(1, 8);
  hex.elements << 4, 5, 6, 7, 0, 1, 2, 3;  // top face first: mirrored
  EXPECT_THROW(validate_mesh(hex, "hex"), Error);
  EXPECT_EQ(reorient_inverted_elements(hex), 1);
  validate_mesh(hex, "hex");
  EXPECT_EQ(reorient_inverted_elements(hex), 0);
}

}  // namespace
}  // namespace sinew
