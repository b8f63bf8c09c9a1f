// Render surfaces through the polygon OBJ reader and writer: polygons, UVs, normals, groups,
// objects, materials and smoothing survive a round trip; normals follow a deformation; every
// malformed line is named; material libraries are copied beside the output.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

#include "io_test_support.hpp"
#include "sinew/io/obj_polygon_reader.hpp"
#include "sinew/io/obj_polygon_writer.hpp"
#include "sinew/io/ply_writer.hpp"
#include "sinew/io/vtk_writer.hpp"

namespace sinew {
namespace {

using test::error_message;
using test::expect_contains;

PolygonSurface cube() { return read_obj_polygon_surface(test::data_path("render/cube_quads.obj")); }

TEST(IoPolygonObj, ReadsQuadsUvsNormalsGroupsMaterials) {
  const PolygonSurface s = cube();
  EXPECT_EQ(s.num_positions(), 9);
  EXPECT_EQ(s.uvs.rows(), 4);
  EXPECT_EQ(s.normals.rows(), 6);
  ASSERT_EQ(s.num_faces(), 6);
  for (Eigen::Index f = 0; f < 6; ++f) EXPECT_EQ(s.face_size(f), 4);
  EXPECT_EQ(s.groups, (std::vector<std::string>{"sides", "caps"}));
  EXPECT_EQ(s.materials, (std::vector<std::string>{"skin", "nail"}));
  EXPECT_EQ(s.objects, (std::vector<std::string>{"RenderCube"}));
  EXPECT_EQ(s.material_libraries, (std::vector<std::string>{"cube_quads.mtl"}));
  EXPECT_EQ(s.face_group, (std::vector<int>{0, 0, 0, 0, 1, 1}));
  EXPECT_EQ(s.face_material, (std::vector<int>{0, 0, 0, 0, 1, 1}));
  EXPECT_EQ(s.face_smoothing, (std::vector<int>(6, 0)));
  // The last face uses negative (relative) indices: -8 of 9 vertices is vertex 2 (index 1).
  const int last = s.face_start[5];
  EXPECT_EQ(s.corners[last].position, 1);
  EXPECT_EQ(s.corners[last].uv, 0);
  EXPECT_EQ(s.corners[last].normal, 5);
  EXPECT_EQ(s.unused_positions(), (std::vector<int>{8}));
  const TriangleSurface t = s.triangulated();
  EXPECT_EQ(t.num_faces(), 12);
  EXPECT_NEAR(t.volume(), 0.8 * 0.8 * 0.8, 1e-12);  // outward quads, fan-split
}

TEST(IoPolygonObj, RoundTripKeepsEverythingAndRecomputesFlatNormals) {
  test::TempDir dir;
  const PolygonSurface s = cube();
  write_obj_polygon_surface(dir / "out.obj", s, s.positions);
  const PolygonSurface r = read_obj_polygon_surface(dir / "out.obj");
  EXPECT_EQ(r.positions, s.positions);  // shortest round-trip text
  EXPECT_EQ(r.uvs, s.uvs);
  EXPECT_EQ(r.face_start, s.face_start);
  EXPECT_EQ(r.groups, s.groups);
  EXPECT_EQ(r.materials, s.materials);
  EXPECT_EQ(r.objects, s.objects);
  EXPECT_EQ(r.face_group, s.face_group);
  EXPECT_EQ(r.face_material, s.face_material);
  EXPECT_EQ(r.face_object, s.face_object);
  EXPECT_EQ(r.face_smoothing, s.face_smoothing);
  EXPECT_EQ(r.material_libraries, s.material_libraries);
  ASSERT_EQ(r.corners.size(), s.corners.size());
  for (size_t c = 0; c < s.corners.size(); ++c) {
    EXPECT_EQ(r.corners[c].position, s.corners[c].position);
    EXPECT_EQ(r.corners[c].uv, s.corners[c].uv);
    // Flat input normals: each corner's recomputed normal is its face's normal, as given.
    EXPECT_LT((r.normals.row(r.corners[c].normal) - s.normals.row(s.corners[c].normal)).norm(), 1e-12) << c;
  }
  // Without objects (the point cache's rest OBJ) there is no "o" line.
  ObjWriteOptions no_objects;
  no_objects.objects = false;
  no_objects.normals = ObjNormals::Omit;
  write_obj_polygon_surface(dir / "plain.obj", s, s.positions, no_objects);
  const std::string text = test::read_file(dir / "plain.obj");
  EXPECT_EQ(text.find("\no "), std::string::npos);
  EXPECT_EQ(text.find("vn "), std::string::npos);
  EXPECT_NE(text.find("f 1/1 4/2 3/3 2/4\n"), std::string::npos);
}

TEST(IoPolygonObj, NormalsFollowTheDeformationAndKeepSmoothVerticesSmooth) {
  test::TempDir dir;
  // A pyramid whose apex shares one normal between its four sides (smooth), base flat.
  const auto path = dir.write("pyramid.obj",
                              "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nv 0 0 1\n"
                              "vn 0 0 1\nvn 0 0 -1\nvn 1 0 0\n"
                              "f 1//2 4//2 3//2 2//2\nf 1//3 2//3 5//1\nf 2//3 3//3 5//1\nf 3//3 4//3 5//1\nf 4//3 1//3 5//1\n");
  const PolygonSurface s = read_obj_polygon_surface(path);
  Eigen::MatrixX3d moved = s.positions;
  moved.col(0) *= 2.0;  // stretched along x
  write_obj_polygon_surface(dir / "moved.obj", s, moved);
  const PolygonSurface r = read_obj_polygon_surface(dir / "moved.obj");
  EXPECT_EQ(r.positions, moved);
  // The base keeps a shared downward normal; the apex keeps one shared normal, now the
  // average of the four stretched sides: straight up by symmetry.
  const Eigen::Vector3d base = r.normals.row(r.corners[0].normal);
  EXPECT_LT((base - Eigen::Vector3d(0, 0, -1)).norm(), 1e-12);
  const int apex = r.corners[r.face_start[1] + 2].normal;
  for (int f = 1; f < 5; ++f) EXPECT_EQ(r.corners[r.face_start[f] + 2].normal, apex);
  EXPECT_LT((Eigen::Vector3d(r.normals.row(apex)) - Eigen::Vector3d(0, 0, 1)).norm(), 1e-12);
  // A side vertex's normal (shared by two sides in the input) is unit and tilts with the stretch.
  const Eigen::Vector3d side = r.normals.row(r.corners[r.face_start[1]].normal);
  EXPECT_NEAR(side.norm(), 1.0, 1e-12);
  EXPECT_GT(side.z(), 0.0);
}

TEST(IoPolygonObj, MalformedLinesAreNamed) {
  test::TempDir dir;
  auto fails = [&](const std::string& text) { return error_message([&] { read_obj_polygon_surface(dir.write("bad.obj", text)); }); };
  expect_contains(fails("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n"), {"bad.obj:4", "index 0"});
  expect_contains(fails("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n"), {"bad.obj:4", "vertex index 4 is out of range"});
  expect_contains(fails("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n"), {"bad.obj:4", "at least 3 corners"});
  expect_contains(fails("v 0 0 nan\n"), {"bad.obj:1", "not finite"});
  expect_contains(fails("v 0 0\n"), {"bad.obj:1", "x y z"});
  expect_contains(fails("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 x\n"), {"bad.obj:4", "expected a number", "'x'"});
  expect_contains(fails("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1 2/1 3/1\n"), {"bad.obj:4", "texture coordinate index 1 is out of range"});
  expect_contains(fails("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1//-2 2 3\n"), {"bad.obj:4", "normal index -2"});
  expect_contains(fails("v 0 0 0\n"), {"bad.obj", "no face"});
  expect_contains(fails("v 0 0 0\nv 1 0 0\nv 0 1 0\ns maybe\nf 1 2 3\n"), {"bad.obj:4", "smoothing group"});
  expect_contains(error_message([&] { read_obj_polygon_surface(dir / "missing.obj"); }), {"missing.obj", "does not exist"});
  // Points, lines and unknown statements carry no surface and are skipped.
  const PolygonSurface ok = read_obj_polygon_surface(dir.write("ok.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\np 3\nvp 0.5\nf 1 2 3\n"));
  EXPECT_EQ(ok.num_faces(), 1);
}

TEST(IoPolygonObj, WriterChecksSizes) {
  test::TempDir dir;
  const PolygonSurface s = cube();
  expect_contains(error_message([&] { write_obj_polygon_surface(dir / "x.obj", s, Eigen::MatrixX3d::Zero(3, 3)); }),
                  {"x.obj", "3 positions given for a surface of 9 vertices"});
  Eigen::MatrixX3d bad = s.positions;
  bad(0, 0) = std::nan("");
  expect_contains(error_message([&] { write_obj_polygon_surface(dir / "x.obj", s, bad); }), {"x.obj", "not finite"});
  EXPECT_FALSE(std::filesystem::exists(dir / "x.obj"));
}

TEST(IoPolygonObj, MaterialLibrariesAreCopiedWithTexturePathsThatStillResolve) {
  test::TempDir dir;
  const PolygonSurface s = cube();
  copy_material_libraries(s, test::data_path("render/cube_quads.obj"), dir.path());
  const std::string mtl = test::read_file(dir / "cube_quads.mtl");
  EXPECT_NE(mtl.find("newmtl skin"), std::string::npos);
  const std::string texture = (std::filesystem::absolute(test::data_path("render")) / "textures/skin.png").lexically_normal().string();
  EXPECT_NE(mtl.find("map_Kd " + texture), std::string::npos) << mtl;
  PolygonSurface missing = s;
  missing.material_libraries = {"nope.mtl"};
  expect_contains(error_message([&] { copy_material_libraries(missing, test::data_path("render/cube_quads.obj"), dir.path()); }),
                  {"cube_quads.obj", "material library 'nope.mtl' not found"});
}

TEST(IoPolygonObj, PlyKeepsPolygonsAndVertexScalars) {
  test::TempDir dir;
  const PolygonSurface s = cube();
  Eigen::VectorXd J = Eigen::VectorXd::LinSpaced(9, 0.5, 1.3);
  write_ply(dir / "c.ply", s, s.positions, {{"J", J}});
  const std::string text = test::read_file(dir / "c.ply");
  expect_contains(text, {"element vertex 9\n", "property double z\nproperty double J\n", "element face 6\n", "\n4 0 3 2 1\n"});
  EXPECT_NE(text.find("-0.4 -0.4 -0.4 0.5\n"), std::string::npos);
  expect_contains(error_message([&] { write_ply(dir / "c.ply", s, s.positions, {{"J", Eigen::VectorXd::Zero(3)}}); }),
                  {"c.ply", "'J' has 3 values, expected 9"});
  expect_contains(error_message([&] { write_ply(dir / "c.ply", s, s.positions, {{"x", J}}); }), {"'x' is repeated or reserved"});
  expect_contains(error_message([&] { write_ply(dir / "c.ply", s, s.positions, {{"von mises", J}}); }), {"not a plain identifier"});
}

TEST(IoPolygonObj, SurfaceVtuHasPolygonCells) {
  test::TempDir dir;
  const PolygonSurface s = cube();
  write_surface_vtu(dir / "c.vtu", s, s.positions);
  const std::string text = test::read_file(dir / "c.vtu");
  expect_contains(text, {"NumberOfPoints=\"9\" NumberOfCells=\"6\"", "Name=\"types\""});
  // VTK's own reader agrees (tests/vtk_reader_check.py; skipped without python3-vtk9).
  const std::string check = "/usr/bin/python3 '" + (test::data_path("..") / "vtk_reader_check.py").string() + "' '" +
                            (dir / "c.vtu").string() + "' --cells 6 --points ";
  if (std::system("/usr/bin/python3 -c 'import vtk' > /dev/null 2>&1") == 0) {
    EXPECT_EQ(std::system((check + "9").c_str()), 0);
    EXPECT_NE(std::system((check + "10 2> /dev/null").c_str()), 0);  // the check can fail
  }
  TriangleSurface bad = s.triangulated();
  bad.faces(0, 0) = 99;
  expect_contains(error_message([&] { write_surface_vtu(dir / "t.vtu", bad); }), {"t.vtu", "refers to vertex 99"});
}

}  // namespace
}  // namespace sinew
