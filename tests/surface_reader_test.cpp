// Surface readers (OBJ and STL through CGAL after checks, OFF and PLY read by Sinew) on the example surfaces and on broken
// files: every rejection names the file and the line, face or edge at fault.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fmt/format.h>
#include <numbers>

#include "io_test_support.hpp"
#include "sinew/io/surface_reader.hpp"
#include "sinew/mesh/triangle_surface.hpp"

namespace sinew {
namespace {

using test::error_message;
using test::expect_contains;
using test::TempDir;

std::filesystem::path example(const std::string& name) { return std::filesystem::path(SINEW_EXAMPLES) / "meshes" / name; }

// A closed tetrahedron (outward faces) as OBJ text, with `extra` appended.
const char* kTetObj =
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
    "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";

TEST(SurfaceReader, ReadsTheExampleSurfacesInAllFourFormats) {
  const TriangleSurface torus_obj = read_triangle_surface(example("torus.obj"));
  const TriangleSurface torus_ply = read_triangle_surface(example("torus.ply"));
  EXPECT_EQ(torus_obj.num_vertices(), 32 * 16);
  EXPECT_EQ(torus_obj.num_faces(), 2 * 32 * 16);
  EXPECT_EQ(torus_ply.faces, torus_obj.faces);
  EXPECT_LT((torus_ply.vertices - torus_obj.vertices).cwiseAbs().maxCoeff(), 1e-12);
  // Polyhedral torus: slightly below 2 pi^2 R r^2.
  const double torus = 2 * std::numbers::pi * std::numbers::pi * 0.35 * 0.15 * 0.15;
  EXPECT_NEAR(torus_obj.volume(), torus, 0.04 * torus);
  EXPECT_TRUE(surface_topology(torus_obj).watertight());

  const TriangleSurface sphere = read_triangle_surface(example("sphere.stl"));  // STL: corners merged by CGAL
  EXPECT_EQ(sphere.num_faces(), 320);
  EXPECT_EQ(sphere.num_vertices(), 162);
  EXPECT_TRUE(surface_topology(sphere).watertight());
  EXPECT_NEAR(sphere.volume(), 4.0 / 3.0 * std::numbers::pi * 0.125, 0.05 * 0.52);

  const TriangleSurface blob = read_triangle_surface(example("blob.off"));
  EXPECT_EQ(blob.num_faces(), 1280);
  EXPECT_TRUE(surface_topology(blob).watertight());

  const TriangleSurface cubes = read_triangle_surface(example("two_cubes_edge.obj"));
  EXPECT_DOUBLE_EQ(cubes.volume(), 2.0);
  const SurfaceTopology t = surface_topology(cubes);
  EXPECT_TRUE(t.closed());
  EXPECT_EQ(t.nonmanifold_edges, 1);  // the shared edge, in four faces
  EXPECT_FALSE(t.watertight());
}

TEST(SurfaceReader, BinaryStlAndQuadsAndNegativeObjIndices) {
  TempDir dir;
  // Binary STL of the tetrahedron.
  const double P[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const int F[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  std::string bytes(80, ' ');
  const std::uint32_t n = 4;
  bytes.append(reinterpret_cast<const char*>(&n), 4);
  for (const auto& f : F) {
    float record[12] = {};
    for (int c = 0; c < 3; ++c)
      for (int i = 0; i < 3; ++i) record[3 + 3 * c + i] = static_cast<float>(P[f[c]][i]);
    bytes.append(reinterpret_cast<const char*>(record), sizeof record);
    bytes.append(2, '\0');
  }
  const TriangleSurface stl = read_triangle_surface(dir.write("tet.stl", bytes));
  EXPECT_EQ(stl.num_vertices(), 4);
  EXPECT_NEAR(stl.volume(), 1.0 / 6.0, 1e-7);
  // A cut-off binary STL names the triangle that is cut.
  expect_contains(error_message([&] { read_triangle_surface(dir.write("cut.stl", bytes.substr(0, bytes.size() - 20))); }),
                  {"cut.stl", "truncated", "triangle 3"});

  // Binary little-endian PLY of the same tetrahedron (float coordinates, uchar/int face lists).
  std::string ply =
      "ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
      "property float z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n";
  for (const auto& p : P)
    for (double c : p) {
      const float x = static_cast<float>(c);
      ply.append(reinterpret_cast<const char*>(&x), 4);
    }
  for (const auto& f : F) {
    ply.push_back('\3');
    for (int c : f) ply.append(reinterpret_cast<const char*>(&c), 4);
  }
  const TriangleSurface from_ply = read_triangle_surface(dir.write("tet.ply", ply));
  EXPECT_EQ(from_ply.num_faces(), 4);
  EXPECT_NEAR(from_ply.volume(), 1.0 / 6.0, 1e-7);
  expect_contains(error_message([&] { read_triangle_surface(dir.write("cut.ply", ply.substr(0, ply.size() - 9))); }),
                  {"cut.ply"});

  // A cube of quads, with relative (negative) indices and texture/normal slots.
  const TriangleSurface cube = read_triangle_surface(dir.write("cube.obj",
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 0 0 1\nv 1 0 1\nv 0 1 1\nv 1 1 1\n"
      "f 1 3 4 2\nf 5 6 8 7\nf 1//1 2//1 6//1 5//1\nf 3 7 8 4\nf 1 5 7 3\nf -7 -5 -1 -3\n"));
  EXPECT_EQ(cube.num_faces(), 12);
  EXPECT_NEAR(cube.volume(), 1.0, 1e-14);
}

// PLY and OFF are read by Sinew itself (CGAL's readers trust the file): positions of any numeric
// type, extra properties and elements walked over, either byte order, the index list found by name.
TEST(SurfaceReader, PlyAndOffOfEveryPropertyLayout) {
  TempDir dir;
  const int P[4][3] = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0, 0, 2}};
  const int F[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  // x double, y uchar, z short, a colour; an edge element; faces with a flag before the list.
  for (const bool big : {false, true}) {
    std::string ply = fmt::format(
        "ply\nformat binary_{}_endian 1.0\ncomment made by a test\nelement vertex 4\nproperty double x\n"
        "property uchar y\nproperty short z\nproperty uchar red\nelement edge 1\nproperty int a\nproperty int b\n"
        "element face 4\nproperty uchar flag\nproperty list uchar uint vertex_index\nend_header\n",
        big ? "big" : "little");
    const auto put = [&](auto value) {
      char b[sizeof value];
      std::memcpy(b, &value, sizeof value);
      if (big) std::reverse(b, b + sizeof value);
      ply.append(b, sizeof value);
    };
    for (const auto& p : P) put(double(p[0])), put(std::uint8_t(p[1])), put(std::int16_t(p[2])), put(std::uint8_t(200));
    put(std::int32_t(0)), put(std::int32_t(1));
    for (const auto& f : F) {
      put(std::uint8_t(7)), put(std::uint8_t(3));
      for (int c : f) put(std::uint32_t(c));
    }
    const TriangleSurface s = read_triangle_surface(dir.write("tet.ply", ply));
    ASSERT_EQ(s.num_vertices(), 4);
    EXPECT_EQ(s.vertices.row(2), Eigen::RowVector3d(0, 2, 0));
    EXPECT_NEAR(s.volume(), 8.0 / 6.0, 1e-14);
  }
  // ASCII with the same layout.
  std::string ascii = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty uchar y\nproperty int z\n"
                      "property uchar red\nelement face 4\nproperty uchar flag\nproperty list uchar int vertex_indices\nend_header\n";
  for (const auto& p : P) ascii += fmt::format("{} {} {} 200\n", p[0], p[1], p[2]);
  for (const auto& f : F) ascii += fmt::format("7 3 {} {} {}\n", f[0], f[1], f[2]);
  EXPECT_NEAR(read_triangle_surface(dir.write("ascii.ply", ascii)).volume(), 8.0 / 6.0, 1e-14);
  // A PLY without a position or without 'ply' first names what is missing.
  std::string no_z = ascii;
  no_z.replace(no_z.find("property int z"), 14, "property int w");
  expect_contains(error_message([&] { read_triangle_surface(dir.write("no_z.ply", no_z)); }), {"no_z.ply:", "'z'"});
  expect_contains(error_message([&] { read_triangle_surface(dir.write("magic.ply", ascii.substr(4))); }),
                  {"magic.ply:1", "'ply'"});
  // COFF rows carry colours after the position; only the position is read.
  std::string coff = "COFF\n4 4 0\n";
  for (const auto& p : P) coff += fmt::format("{} {} {} 255 0 0 255\n", p[0], p[1], p[2]);
  for (const auto& f : F) coff += fmt::format("3 {} {} {} 10 20 30\n", f[0], f[1], f[2]);
  EXPECT_NEAR(read_triangle_surface(dir.write("tet.off", coff)).volume(), 8.0 / 6.0, 1e-14);
  expect_contains(error_message([&] { read_triangle_surface(dir.write("huge.off", "OFF\n2000000000 1 0\n0 0 0\n")); }),
                  {"huge.off:2", "do not fit"});
}

TEST(SurfaceReader, BrokenFilesNameTheFileAndTheLine) {
  TempDir dir;
  auto message = [&](const std::string& name, const std::string& text) {
    const auto path = dir.write(name, text);
    return error_message([&] { read_triangle_surface(path); });
  };
  expect_contains(message("nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n"),
                  {"nan.obj:2", "finite number", "nan"});
  expect_contains(message("short.obj", std::string(kTetObj).substr(0, std::strlen(kTetObj) - 3)),
                  {"short.obj:8", "at least three vertices"});
  expect_contains(message("index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n"), {"index.obj:4", "7", "out of range"});
  expect_contains(message("coords.obj", "v 0 0\n"), {"coords.obj:1", "three coordinates"});
  expect_contains(message("cut.off", "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n"),
                  {"cut.off:8", "ends early", "2 of 4 faces"});
  expect_contains(message("inf.off", "OFF\n4 4 0\n0 0 0\n1 0 0\n0 inf 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n"),
                  {"inf.off:5", "finite"});
  expect_contains(message("bad.ply",
                          "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
                          "element face 4\nproperty list uchar int vertex_indices\nend_header\n"
                          "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 9\n3 1 2 3\n"),
                  {"bad.ply:16", "out of range"});
  expect_contains(message("cut.stl", "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"),
                  {"cut.stl", "ends early"});
  expect_contains(message("empty.obj", ""), {"empty.obj", "empty"});
  expect_contains(message("shape.xyz", "1 2 3"), {"shape.xyz", "unknown surface file extension"});
  expect_contains(error_message([&] { read_triangle_surface(dir / "missing.obj"); }), {"missing.obj"});
}

TEST(SurfaceReader, RejectsOpenDegenerateAndInsideOutSurfaces) {
  TempDir dir;
  auto message = [&](const std::string& name, const std::string& text) {
    const auto path = dir.write(name, text);
    return error_message([&] { read_triangle_surface(path); });
  };
  const std::string verts = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n";
  expect_contains(message("open.obj", verts + "f 1 3 2\nf 1 2 4\nf 1 4 3\n"), {"open.obj", "not closed", "face 0"});
  expect_contains(message("repeat.obj", verts + "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 3\n"), {"repeat.obj", "face 3", "degenerate"});
  expect_contains(message("flat.obj", verts + "v 0.5 0 0\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\nf 1 2 5\n"),
                  {"flat.obj", "face 4"});
  expect_contains(message("flipped.obj", verts + "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 4 3\n"),
                  {"flipped.obj", "not consistently oriented", "face"});
  expect_contains(message("inside_out.obj", verts + "f 1 2 3\nf 1 4 2\nf 1 3 4\nf 2 4 3\n"),
                  {"inside_out.obj", "non-positive volume"});
  // An open surface is fine where closure is not required.
  const TriangleSurface open = read_triangle_surface(dir.write("open2.obj", verts + "f 1 3 2\nf 1 2 4\n"), false);
  EXPECT_EQ(surface_topology(open).boundary_edges, 4);
}

}  // namespace
}  // namespace sinew
