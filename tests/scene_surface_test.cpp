// The surface keys of a scene's /mesh: voxelised and tetrahedralised surfaces, the embedded
// surface, reoriented mesh files, and the errors for misplaced or missing keys.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "io_test_support.hpp"
#include "sinew/io/surface_reader.hpp"
#include "sinew/model/scene.hpp"
#include "sinew/run/simulation.hpp"

namespace sinew {
namespace {

using nlohmann::json;
using test::error_message;
using test::expect_contains;

std::filesystem::path meshes() { return std::filesystem::path(SINEW_EXAMPLES) / "meshes"; }

json scene_with(const json& mesh) {
  return {{"mesh", mesh}, {"material", {{"family", "stable_neo_hookean"}, {"E", 1e5}, {"nu", 0.3}}}};
}

std::string failure(const json& mesh) {
  return error_message([&] { build_scene_mesh(parse_scene(scene_with(mesh), meshes() / "scene.json")); });
}

TEST(SceneSurface, VoxelisedAndTetrahedralisedSurfaces) {
  const Scene v = parse_scene(scene_with({{"surface", "torus.obj"}, {"cell_size", 0.1}, {"embed", true}}), meshes() / "s.json");
  ASSERT_TRUE(std::holds_alternative<SurfaceVoxels>(v.mesh.source));
  EXPECT_EQ(std::get<SurfaceVoxels>(v.mesh.source).path, meshes() / "torus.obj");
  ASSERT_TRUE(v.mesh.embed.has_value());
  EXPECT_EQ(*v.mesh.embed, meshes() / "torus.obj");
  const VolumeMesh hexes = build_scene_mesh(v);
  EXPECT_EQ(hexes.kind, ElementKind::Hex8);
  EXPECT_GT(hexes.num_elements(), 50);

  const Scene t = parse_scene(scene_with({{"surface", "two_cubes_edge.obj"}, {"resolution", 2}, {"non_manifold", true},
                                          {"element", "tet"}}),
                              meshes() / "s.json");
  EXPECT_FALSE(t.mesh.embed.has_value());
  const VolumeMesh tets = build_scene_mesh(t);
  EXPECT_EQ(tets.kind, ElementKind::Tet4);
  EXPECT_EQ(tets.num_elements(), 2 * 6);
  EXPECT_EQ(tets.num_vertices(), 16);  // two cubes of 8 corners, the shared edge duplicated

  const Scene g = parse_scene(scene_with({{"tetrahedralize", "sphere.stl"}, {"max_edge", 0.5}}), meshes() / "s.json");
  EXPECT_EQ(build_scene_mesh(g).kind, ElementKind::Tet4);
}

TEST(SceneSurface, AnyMeshCanEmbedASurfaceFile) {
  test::TempDir dir;
  // The example sphere (radius 0.5 at the origin) inside a box lattice, written every frame.
  const std::string scene = R"({
    "mesh": {"box": {"min": [-0.6, -0.6, -0.6], "max": [0.6, 0.6, 0.6]}, "cells": [3, 3, 3], "embed": ")" +
                            (meshes() / "sphere.stl").string() + R"("},
    "material": {"family": "stable_neo_hookean", "E": 1e5, "nu": 0.3},
    "boundary": [{"name": "base", "select": {"plane": {"point": [0, 0, -0.6], "normal": [0, 0, -1]}}},
                 {"name": "top", "select": {"plane": {"point": [0, 0, 0.6], "normal": [0, 0, 1]}},
                  "motion": {"type": "translate", "per_frame": [0.05, 0, 0]}}]
  })";
  RunOptions options;
  options.out_dir = dir / "out";
  ASSERT_TRUE(run_scene(load_scene(dir.write("box.json", scene)), options).all_converged());
  const TriangleSurface sphere = read_triangle_surface(meshes() / "sphere.stl");
  const TriangleSurface moved = read_triangle_surface(dir / "out" / "embedded_surface_0001.ply");
  EXPECT_EQ(moved.faces, sphere.faces);
  EXPECT_GT((moved.vertices - sphere.vertices).cwiseAbs().maxCoeff(), 0.01);
}

TEST(SceneSurface, MisplacedOrMissingKeysAreNamed) {
  expect_contains(failure({{"surface", "torus.obj"}}), {"/mesh", "exactly one of cell_size or resolution"});
  expect_contains(failure({{"surface", "torus.obj"}, {"resolution", 4}, {"box", {{"min", {0, 0, 0}}, {"max", {1, 1, 1}}}}}),
                  {"/mesh/box", "not allowed with surface"});
  expect_contains(failure({{"surface", "missing.obj"}, {"resolution", 4}}), {"/mesh/surface", "surface file not found", "missing.obj"});
  expect_contains(failure({{"tetrahedralize", "blob.off"}, {"resolution", 4}, {"max_edge", 0.1}}), {"/mesh/resolution", "max_edge"});
  expect_contains(failure({{"tetrahedralize", "blob.off"}}), {"/mesh/max_edge"});
  expect_contains(failure({{"surface", "torus.obj"}, {"resolution", 4}, {"max_edge", 0.1}}), {"/mesh/max_edge"});
  expect_contains(failure({{"box", {{"min", {0, 0, 0}}, {"max", {1, 1, 1}}}}, {"cells", {1, 1, 1}}, {"embed", true}}),
                  {"/mesh/embed", "name a surface file"});
  expect_contains(failure({{"box", {{"min", {0, 0, 0}}, {"max", {1, 1, 1}}}}, {"cells", {1, 1, 1}}, {"embed", 3}}),
                  {"/mesh/embed", "true, false or a surface file"});
  expect_contains(failure({{"box", {{"min", {0, 0, 0}}, {"max", {1, 1, 1}}}}, {"cells", {1, 1, 1}}, {"embed", "nope.obj"}}),
                  {"/mesh/embed", "surface file not found"});
  expect_contains(failure({{"tetrahedralize", "two_cubes_edge.obj"}, {"max_edge", 0.5}}), {"/mesh", "2-manifold"});
}

TEST(SceneSurface, BrokenSurfaceFileIsReportedWithSceneFileAndLine) {
  test::TempDir dir;
  dir.write("open.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\n");
  dir.write("nan.obj", "v 0 0 0\nv 1 0 nan\n");
  auto message = [&](const std::string& file) {
    return error_message([&] {
      build_scene_mesh(parse_scene(scene_with({{"surface", file}, {"resolution", 3}}), dir / "scene.json"));
    });
  };
  expect_contains(message("open.obj"), {"scene.json: /mesh", "open.obj", "not closed", "face 0"});
  expect_contains(message("nan.obj"), {"scene.json: /mesh", "nan.obj:2"});
}

TEST(SceneSurface, ReorientedMeshFile) {
  test::TempDir dir;
  dir.write("inv.node", "4 3 0 0\n0 0 0 0\n1 1 0 0\n2 0 1 0\n3 0 0 1\n");
  dir.write("inv.ele", "1 4 0\n0 0 2 1 3\n");
  const json plain = scene_with({{"file", "inv.ele"}});
  expect_contains(error_message([&] { build_scene_mesh(parse_scene(plain, dir / "s.json")); }), {"/mesh/file", "inv.ele", "element 0"});
  const json fixed = scene_with({{"file", "inv.ele"}, {"reorient", true}});
  EXPECT_EQ(build_scene_mesh(parse_scene(fixed, dir / "s.json")).num_elements(), 1);
}

}  // namespace
}  // namespace sinew
