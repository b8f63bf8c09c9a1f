// Production output of a run: the embedded render surface keeps its quads, UVs, groups and
// materials; its point cache matches the per-frame OBJs and survives a resume; per-vertex J is
// in the PLY; obstacles and bones are written per frame; the .pvd says what its time means.
#include <gtest/gtest.h>

#include <fmt/format.h>
#include <sstream>

#include "io_test_support.hpp"
#include "sinew/io/obj_polygon_reader.hpp"
#include "sinew/io/point_cache.hpp"
#include "sinew/io/surface_reader.hpp"
#include "sinew/run/simulation.hpp"

namespace sinew {
namespace {

std::string quasistatic_scene() {
  return R"({
    "mesh": {"box": {"min": [-0.6, -0.6, -0.6], "max": [0.6, 0.6, 0.6]}, "cells": [3, 3, 3],
             "embed": ")" + test::data_path("render/cube_quads.obj").string() + R"("},
    "material": {"family": "stable_neo_hookean", "E": 1e5, "nu": 0.3},
    "boundary": [{"name": "base", "select": {"plane": {"point": [0, 0, -0.6], "normal": [0, 0, -1]}}}],
    "obstacles": [{"name": "far ball", "type": "sphere", "center": [0, 0, 5], "radius": 0.5, "stiffness": 1e6}],
    "rig": {"bones": [{"name": "top", "capsule": {"a": [-0.6, 0, 0.6], "b": [0.6, 0, 0.6], "radius": 0.7},
                       "keys": [{"frame": 0}, {"frame": 2, "translation": [0.05, 0, 0]}]}]},
    "frames": 2
  })";
}

RunSummary run(const std::filesystem::path& scene, const std::filesystem::path& out, std::optional<int> frames = {},
               bool resume = false) {
  RunOptions options;
  options.out_dir = out;
  options.frames = frames;
  options.resume = resume;
  return run_scene(load_scene(scene), options);
}

TEST(ProductionOutput, RenderSurfacePointCacheShapesAndPvd) {
  test::TempDir dir;
  const auto scene = dir.write("scene.json", quasistatic_scene());
  ASSERT_TRUE(run(scene, dir / "out").all_converged());
  const auto out = dir / "out";
  const PolygonSurface input = read_obj_polygon_surface(test::data_path("render/cube_quads.obj"));

  // Per-frame OBJ: everything but positions and normals as read.
  const PolygonSurface moved = read_obj_polygon_surface(out / "embedded_surface_0002.obj");
  EXPECT_EQ(moved.face_start, input.face_start);  // quads stay quads
  EXPECT_EQ(moved.uvs, input.uvs);
  EXPECT_EQ(moved.groups, input.groups);
  EXPECT_EQ(moved.materials, input.materials);
  EXPECT_EQ(moved.objects, input.objects);
  EXPECT_EQ(moved.face_material, input.face_material);
  EXPECT_EQ(moved.material_libraries, input.material_libraries);
  EXPECT_GT((moved.positions - input.positions).cwiseAbs().maxCoeff(), 1e-3);  // the bone moved it
  EXPECT_NEAR(moved.normals.rowwise().norm().minCoeff(), 1.0, 1e-12);
  EXPECT_TRUE(std::filesystem::exists(out / "cube_quads.mtl"));

  // Point cache: one sample per frame, the used vertices of each frame's OBJ, in rest-OBJ order.
  const PolygonSurface rest = read_obj_polygon_surface(out / "embedded_surface_rest.obj");
  EXPECT_EQ(rest.num_positions(), 8);  // the unused 9th vertex is left out, as Blender's importer does
  EXPECT_TRUE(rest.objects.empty());
  EXPECT_EQ(rest.positions, input.positions.topRows(8));
  const PointCache cache = read_pc2(out / "embedded_surface.pc2");
  ASSERT_EQ(cache.samples.size(), 3u);
  EXPECT_EQ(cache.start_frame, 0.0f);
  EXPECT_EQ(cache.sample_rate, 1.0f);
  for (int f = 0; f <= 2; ++f) {
    const PolygonSurface at = read_obj_polygon_surface(out / fmt::format("embedded_surface_{:04d}.obj", f));
    EXPECT_LT((cache.samples[f].cast<double>() - at.positions.topRows(8)).cwiseAbs().maxCoeff(), 1e-6) << f;
  }

  // PLY: the polygons with per-vertex J and stress_norm; J = 1 at rest.
  const std::string ply0 = test::read_file(out / "embedded_surface_0000.ply");
  test::expect_contains(ply0, {"property double J\nproperty double stress_norm\n", "element face 6\n"});
  std::istringstream rows(ply0.substr(ply0.find("end_header\n") + 11));
  for (int v = 0; v < 9; ++v) {
    double x, y, z, J, stress;
    ASSERT_TRUE(rows >> x >> y >> z >> J >> stress) << v;
    EXPECT_NEAR(x, input.positions(v, 0), 1e-12);
    EXPECT_NEAR(J, 1.0, v < 8 ? 1e-12 : 1e-9) << v;  // vertex 8 lies far outside: extrapolated weights
    EXPECT_NEAR(stress, 0.0, 1e-6) << v;
  }

  // Obstacles and bones, per frame; the bone's surface follows its key.
  for (const char* stem : {"obstacle_far_ball", "bone_top"})
    for (const char* ext : {"vtu", "obj"})
      for (int f = 0; f <= 2; ++f)
        EXPECT_TRUE(std::filesystem::exists(out / fmt::format("{}_{:04d}.{}", stem, f, ext))) << stem << f << ext;
  const TriangleSurface bone0 = read_triangle_surface(out / "bone_top_0000.obj");
  const TriangleSurface bone2 = read_triangle_surface(out / "bone_top_0002.obj");
  EXPECT_LT(((bone2.vertices - bone0.vertices).rowwise() - Eigen::RowVector3d(0.05, 0, 0)).cwiseAbs().maxCoeff(), 1e-12);

  const std::string pvd = test::read_file(out / "simulation.pvd");
  test::expect_contains(pvd, {"timestep: frame number (quasistatic run", "timestep=\"2\""});

  // A resumed run cuts the cache back to the checkpoint and continues it.
  ASSERT_TRUE(run(scene, dir / "resumed", 1).all_converged());
  EXPECT_EQ(read_pc2(dir / "resumed" / "embedded_surface.pc2").samples.size(), 2u);
  ASSERT_TRUE(run(scene, dir / "resumed", 2, true).all_converged());
  const PointCache resumed = read_pc2(dir / "resumed" / "embedded_surface.pc2");
  ASSERT_EQ(resumed.samples.size(), 3u);
  EXPECT_LT((resumed.samples[2] - cache.samples[2]).cwiseAbs().maxCoeff(), 1e-5);
}

TEST(ProductionOutput, DynamicRunsPutSecondsInThePvd) {
  test::TempDir dir;
  const auto scene = dir.write("drop.json", R"({
    "mesh": {"box": {"min": [-0.1, -0.1, 0.05], "max": [0.1, 0.1, 0.15]}, "cells": [2, 2, 1]},
    "material": {"family": "stable_neo_hookean", "E": 1e5, "nu": 0.3},
    "loads": {"gravity": [0, 0, -9.81]},
    "dynamics": {"time_step": 0.01},
    "obstacles": [{"name": "ground", "type": "plane", "point": [0, 0, 0], "normal": [0, 0, 1], "stiffness": 1e7}],
    "frames": 2
  })");
  ASSERT_TRUE(run(scene, dir / "out").all_converged());
  const std::string pvd = test::read_file(dir / "out" / "simulation.pvd");
  test::expect_contains(pvd, {"timestep: simulated time in seconds (dynamic run)", "timestep=\"0.02\"", "timestep=\"0.01\""});
  const TriangleSurface ground = read_triangle_surface(dir / "out" / "obstacle_ground_0002.obj", false);
  EXPECT_EQ(ground.num_faces(), 2);
  EXPECT_TRUE(std::filesystem::exists(dir / "out" / "obstacle_ground_0002.vtu"));
}

}  // namespace
}  // namespace sinew
