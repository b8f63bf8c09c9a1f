// Regression tests for issue 13's defect classes (hostile input): sizes from input that
// overflowed, nesting that recursed without bound, header counts that drove allocation, and
// results that were silently wrong. Each test feeds the kind of input that used to crash, hang
// or pass, and asserts a sinew::Error that names the file and where in it.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "io_test_support.hpp"
#include "sinew/motion/prescribed_motion.hpp"
#include "sinew/io/mesh_reader.hpp"
#include "sinew/io/surface_reader.hpp"
#include "sinew/mesh/inside_test.hpp"
#include "sinew/mesh/lattice.hpp"
#include "sinew/mesh/tetrahedralize_surface.hpp"
#include "sinew/mesh/voxelize.hpp"
#include "sinew/model/rig_reader.hpp"
#include "sinew/model/json_reader.hpp"
#include "sinew/model/scene.hpp"

namespace sinew {
namespace {

using nlohmann::json;
using test::error_message;
using test::expect_contains;

json scene_with(const json& mesh) {
  return {{"mesh", mesh}, {"material", {{"family", "stable_neo_hookean"}, {"E", 1e5}, {"nu", 0.3}}}};
}

// ---- sizes from input: checked 64-bit products and one cell limit on every path ----

TEST(HostileInput, VoxelDimsWhoseIntProductWrapsAreRejected) {
  // 603 * 683 * 20857 = 2 * 2^32 + 1: as an int product it wrapped to 1, matched the one occupancy
  // entry, and the lattice then read 8.6e9 cells from a list of one.
  const std::string m = error_message([] {
    parse_scene(scene_with({{"voxels", {{"min", {0, 0, 0}}, {"max", {1, 1, 1}}, {"dims", {603, 683, 20857}},
                                        {"occupancy", {1}}}}}),
                "wrap.json");
  });
  expect_contains(m, {"wrap.json", "/mesh/voxels/dims", "limit"});
  // Within int but over the cell limit: the limit applies to voxel shapes too.
  expect_contains(error_message([] {
                    parse_scene(scene_with({{"voxels", {{"min", {0, 0, 0}}, {"max", {1, 1, 1}}, {"dims", {1000, 1000, 51}},
                                                        {"occupancy", {1}}}}}),
                                "big.json");
                  }),
                  {"big.json", "/mesh/voxels/dims", "50000000"});
}

TEST(HostileInput, CellCountsOverTheLimitAreRejectedOnEveryPath) {
  expect_contains(error_message([] {
                    parse_scene(scene_with({{"box", {{"min", {0, 0, 0}}, {"max", {1, 1, 1}}}}, {"cells", {1000000, 1000000, 2}}}),
                                "cells.json");
                  }),
                  {"cells.json", "/mesh/cells", "limit"});
  // A tiny cell size once made round(1e20) overflow the int cast and silently built one element.
  for (const double h : {1e-20, 1e-300}) {
    const Scene s = parse_scene(scene_with({{"box", {{"min", {0, 0, 0}}, {"max", {1, 1, 1}}}}, {"cell_size", h}}), "tiny.json");
    expect_contains(error_message([&] { build_scene_mesh(s); }), {"tiny.json", "/mesh/cell_size", "limit"});
  }
  const Scene s = parse_scene(scene_with({{"sphere", {{"center", {0, 0, 0}}, {"radius", 1e100}}}, {"resolution", 2}}), "s.json");
  EXPECT_EQ(build_scene_mesh(s).num_elements(), 8);  // a huge extent at a sane resolution is fine

  // The library calls check the same limit (the lattice builders and voxelisation).
  expect_contains(error_message([] { box_lattice({0, 0, 0}, {1, 1, 1}, Eigen::Vector3i(65536, 65536, 1)); }), {"limit"});
  expect_contains(error_message([] { box_lattice({0, 0, 0}, {1, 1, 1}, Eigen::Vector3i(-1, 1, 1)); }), {"positive"});
  EXPECT_EQ(lattice_cell_counts({1, 2, 3}, 1.0, false, "x"), Eigen::Vector3i(1, 2, 3));
  EXPECT_EQ(lattice_cell_counts({1, 2, 3}, 0.4, true, "x"), Eigen::Vector3i(3, 5, 8));
  expect_contains(error_message([] { lattice_cell_counts({1, 1, 1}, 1e-20, true, "here"); }), {"here", "limit"});
  expect_contains(error_message([] { lattice_cell_counts({1, 1, 1}, 0.0, true, "here"); }), {"here", "positive"});

  TriangleSurface cube;
  cube.vertices.resize(8, 3);
  for (int v = 0; v < 8; ++v) cube.vertices.row(v) << (v & 1), (v >> 1) & 1, (v >> 2) & 1;
  VoxelizeOptions o;
  o.cell_size = 1e-20;
  cube.faces.resize(12, 3);
  cube.faces << 0, 2, 3, 0, 3, 1, 4, 5, 7, 4, 7, 6, 0, 1, 5, 0, 5, 4, 2, 6, 7, 2, 7, 3, 0, 4, 6, 0, 6, 2, 1, 3, 7, 1, 7, 5;
  expect_contains(error_message([&] { voxelize_surface(InsideTest(cube), o); }), {"voxelize", "limit"});
}

// ---- nesting: bounded depth, no recursion on input size ----

TEST(HostileInput, DeeplyNestedVtuIsAnErrorNotAStackOverflow) {
  test::TempDir dir;
  std::string xml;
  for (int i = 0; i < 20000; ++i) xml += "<a>";
  for (int i = 0; i < 20000; ++i) xml += "</a>";
  expect_contains(error_message([&] { read_volume_mesh(dir.write("deep.vtu", xml)); }), {"deep.vtu:1", "nested more than"});
}

TEST(HostileInput, DeeplyNestedJsonIsAnErrorNotAStackOverflow) {
  test::TempDir dir;
  const std::string deep = std::string(100000, '[') + std::string(100000, ']');
  // In a file: refused while parsing, with the file and the path reached.
  const std::string scene = R"({"mesh": {"box": {"min": )" + deep + R"(, "max": [1, 1, 1]}}})";
  expect_contains(error_message([&] { load_scene(dir.write("deep.json", scene)); }),
                  {"deep.json", "/mesh/box/min/0/0", "nested more than 64"});
  expect_contains(error_message([&] { load_rig(dir.write("deep_rig.json", R"({"bones": )" + deep + "}")); }),
                  {"deep_rig.json", "/bones/0", "nested more than 64"});
  // A deep value built in memory (parse_scene's callers) gets a short, bounded description.
  const json j = json::parse(scene, nullptr, true, false);
  const std::string m = error_message([&] { parse_scene(j, "mem.json"); });
  expect_contains(m, {"mem.json", "/mesh/box/min", "must be an array of 3 numbers", "[[[...]]]"});
  EXPECT_LT(m.size(), 300u);
}

// ---- header counts: checked against the file's size before anything is allocated ----

// Reading must fail fast (no gigabytes allocated, no minutes spent) with the file and line.
void expect_quick_error(const std::filesystem::path& file, std::initializer_list<const char*> parts) {
  const auto start = std::chrono::steady_clock::now();
  const std::string m = error_message([&] { read_volume_mesh(file); });
  expect_contains(m, parts);
  EXPECT_EQ(m.find("bad_alloc"), std::string::npos) << m;
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0) << m;
}

TEST(HostileInput, HugeHeaderCountsInMeshFilesAreErrorsNamingTheLine) {
  test::TempDir dir;
  const std::string vtk = "# vtk DataFile Version 4.2\nt\nASCII\nDATASET UNSTRUCTURED_GRID\n";
  expect_quick_error(dir.write("points.vtk", vtk + "POINTS 2147483647 double\n0 0 0\n"), {"points.vtk:5", "cannot be right"});
  const std::string points = "POINTS 4 double\n0 0 0 1 0 0 0 1 0 0 0 1\n";
  expect_quick_error(dir.write("cells.vtk", vtk + points + "CELLS 2000000000 2000000000\n4 0 1 2 3\n"),
                     {"cells.vtk:7", "cannot be right"});
  expect_quick_error(dir.write("offsets.vtk", vtk + points + "CELLS 2 2147483647\nOFFSETS vtktypeint64\n0 4\n"),
                     {"offsets.vtk:7", "cannot be right"});
  expect_quick_error(dir.write("types.vtk", vtk + points + "CELLS 1 5\n4 0 1 2 3\nCELL_TYPES 2147483647\n10\n"),
                     {"types.vtk:9", "cannot be right"});
  expect_quick_error(dir.write("v.mesh", "MeshVersionFormatted 2\nDimension 3\nVertices\n2147483647\n0 0 0 0\n"),
                     {"v.mesh:4", "cannot be right"});
  expect_quick_error(dir.write("t.mesh", "MeshVersionFormatted 2\nDimension 3\nVertices\n1\n0 0 0 0\nTetrahedra\n2147483647\n"),
                     {"t.mesh:7", "cannot be right"});
  expect_quick_error(dir.write("n.msh", "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n2147483648\n1 0 0 0\n"),
                     {"n.msh:5", "cannot be right"});
  expect_quick_error(dir.write("b.msh", "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 1 1 1\n3 1 0 2147483648\n"),
                     {"b.msh:6", "cannot be right"});
  dir.write("huge.ele", "1 4 0\n0 0 1 2 3\n");
  expect_quick_error(dir.write("huge.node", "2147483648 3 0 0\n0 0 0 0\n"), {"huge.node:1", "cannot be right"});
  const std::string vtu = R"(<VTKFile type="UnstructuredGrid"><UnstructuredGrid><Piece NumberOfPoints="2147483647" NumberOfCells="1">
<Points><DataArray type="Float64" NumberOfComponents="3" format="ascii">0 0 0</DataArray></Points></Piece></UnstructuredGrid></VTKFile>)";
  expect_quick_error(dir.write("points.vtu", vtu), {"points.vtu:2", "cannot hold"});
}

TEST(HostileInput, BinaryPlyCountsAreCheckedBeforeCgalReadsThem) {
  test::TempDir dir;
  const std::string header =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 2147483647\nproperty list uchar int vertex_indices\nend_header\n";
  std::string body(36, '\0');  // three vertices at the origin, then no faces at all
  const auto file = dir.write("faces.ply", header + body);
  const std::string m = error_message([&] { read_triangle_surface(file); });
  expect_contains(m, {"faces.ply: byte", "2147483647 rows"});
  // A face index past the vertices, and a NaN coordinate, are named with their byte offset.
  std::string face = std::string(1, '\3');
  for (int v : {0, 1, 7}) face.append(reinterpret_cast<const char*>(&v), 4);
  const size_t count_at = header.find("2147483647");
  const std::string bad = header.substr(0, count_at) + "1" + header.substr(count_at + 10);
  expect_contains(error_message([&] { read_triangle_surface(dir.write("index.ply", bad + body + face)); }),
                  {"index.ply: byte", "face 0 refers to vertex 7"});
  std::string nan_body = body;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  nan_body.replace(4, 4, reinterpret_cast<const char*>(&nan), 4);
  expect_contains(error_message([&] { read_triangle_surface(dir.write("nan.ply", bad + nan_body + face)); }),
                  {"nan.ply: byte", "vertex 0", "not a finite number"});
}

// ---- results that were silently wrong ----

TriangleSurface unit_cube() {
  TriangleSurface cube;
  cube.vertices.resize(8, 3);
  for (int v = 0; v < 8; ++v) cube.vertices.row(v) << (v & 1), (v >> 1) & 1, (v >> 2) & 1;
  cube.faces.resize(12, 3);
  cube.faces << 0, 2, 3, 0, 3, 1, 4, 5, 7, 4, 7, 6, 0, 1, 5, 0, 5, 4, 2, 6, 7, 2, 7, 3, 0, 4, 6, 0, 6, 2, 1, 3, 7, 1, 7, 5;
  return cube;
}

double longest_edge(const Eigen::MatrixX3d& v, const Eigen::MatrixXi& elements) {
  double longest = 0.0;
  for (Eigen::Index e = 0; e < elements.rows(); ++e)
    for (Eigen::Index a = 0; a < elements.cols(); ++a)
      for (Eigen::Index b = a + 1; b < elements.cols(); ++b)
        longest = std::max(longest, (v.row(elements(e, a)) - v.row(elements(e, b))).norm());
  return longest;
}

TEST(HostileInput, BisectingLongSurfaceEdgesKeepsTheSurfaceClosedAndItsShape) {
  const TriangleSurface cube = unit_cube();
  cube.validate("cube");
  const TriangleSurface fine = bisect_long_edges(cube, 0.3);
  fine.validate("fine");  // closed, oriented, no degenerate faces
  EXPECT_TRUE(surface_topology(fine).watertight());
  EXPECT_LE(longest_edge(fine.vertices, fine.faces), 0.3);
  EXPECT_NEAR(fine.volume(), 1.0, 1e-12);
  EXPECT_TRUE(fine.vertices.topRows(8).isApprox(cube.vertices));  // existing vertices keep their indices
  EXPECT_EQ(bisect_long_edges(cube, 2.0).num_faces(), 12);      // nothing longer: unchanged
  expect_contains(error_message([&] { bisect_long_edges(cube, 1e-6, 10000); }), {"max_edge", "too small", "10000"});
}

TEST(HostileInput, TetrahedralizeHonoursMaxEdgeOnACoarseSurface) {
  // A cube of 12 triangles gave 6 tetrahedra whatever max_edge was.
  const VolumeMesh coarse = tetrahedralize_surface(unit_cube(), 2.0);
  const VolumeMesh fine = tetrahedralize_surface(unit_cube(), 0.25);
  EXPECT_GT(fine.num_elements(), 20 * coarse.num_elements());
  EXPECT_LE(longest_edge(fine.vertices, fine.elements), 2 * 0.25);  // Gmsh's sizes are targets, not bounds
  double volume = 0.0;
  for (Eigen::Index e = 0; e < fine.num_elements(); ++e) {
    const Eigen::Vector3d a = fine.vertices.row(fine.elements(e, 0)), b = fine.vertices.row(fine.elements(e, 1)),
                          c = fine.vertices.row(fine.elements(e, 2)), d = fine.vertices.row(fine.elements(e, 3));
    volume += std::abs((b - a).cross(c - a).dot(d - a)) / 6.0;
  }
  EXPECT_NEAR(volume, 1.0, 1e-9);
}

TEST(HostileInput, AMotionThatOverflowsNamesItsSourceAndFrame) {
  const Eigen::MatrixX3d rest = Eigen::MatrixX3d::Zero(2, 3);
  std::vector<KinematicCondition> conditions = {{{1}, Translation{Eigen::Vector3d(1e308, 0, 0)}, "s.json: /boundary/0/motion", {true, true, true}, {}}};
  Eigen::VectorXd x = Eigen::VectorXd::Zero(6);
  std::vector<char> fixed(6, 0);
  apply_kinematics(conditions, rest, 1.0, x, fixed);  // 1e308: still finite
  EXPECT_EQ(x(3), 1e308);
  expect_contains(error_message([&] { apply_kinematics(conditions, rest, 3.0, x, fixed); }),
                  {"s.json: /boundary/0/motion", "frame 3", "vertex 1"});
}

TEST(HostileInput, RigFilesRejectDuplicateKeysLikeSceneFiles) {
  test::TempDir dir;
  const auto rig = dir.write("dup.json", R"({"bones": [{"name": "a", "name": "b",
    "capsule": {"a": [0, 0, 0], "b": [1, 0, 0], "radius": 0.1}, "keys": [{"frame": 0}]}]})");
  expect_contains(error_message([&] { load_rig(rig); }), {"dup.json", "/bones/0/name", "duplicate key"});
  const auto scene = dir.write("dup_scene.json", R"({"frames": 1, "frames": 2})");
  expect_contains(error_message([&] { load_scene(scene); }), {"dup_scene.json", "/frames", "duplicate key"});
}

}  // namespace
}  // namespace sinew
