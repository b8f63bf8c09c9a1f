// Inside test and voxelisation of closed surfaces: a sphere classified correctly, lattice
// volume converging to the surface's, and the non-manifold option splitting two cubes that
// touch along an edge (shared vertices without it, none with it, and no mechanical coupling).
#include <gtest/gtest.h>

#include <cmath>
#include <fmt/format.h>
#include <numbers>
#include <random>
#include <array>
#include <map>
#include <set>

#include "io_test_support.hpp"
#include "sinew/element/mesh_validation.hpp"
#include "sinew/io/mesh_reader.hpp"
#include "sinew/io/surface_reader.hpp"
#include "sinew/mesh/inside_test.hpp"
#include "sinew/mesh/voxelize.hpp"
#include "sinew/run/simulation.hpp"

namespace sinew {
namespace {

using test::TempDir;

std::filesystem::path example(const std::string& name) { return std::filesystem::path(SINEW_EXAMPLES) / "meshes" / name; }

double lattice_volume(const VolumeMesh& m) {
  const Eigen::Vector3d d = m.vertices.row(m.elements(0, 6)) - m.vertices.row(m.elements(0, 0));
  return static_cast<double>(m.num_elements()) * d.prod();
}

TEST(InsideTest, ClassifiesPointsOfASphere) {
  // Icosphere of radius 0.5: points closer to the sphere than its chord error are ambiguous.
  const TriangleSurface sphere = read_triangle_surface(example("sphere.stl"));
  const InsideTest inside(sphere);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.8, 0.8);
  int tested = 0;
  for (int i = 0; i < 4000; ++i) {
    const Eigen::Vector3d p(u(rng), u(rng), u(rng));
    const double r = p.norm();
    if (std::abs(r - 0.5) < 0.03) continue;
    EXPECT_EQ(inside.inside(p), r < 0.5) << p.transpose();
    ++tested;
  }
  EXPECT_GT(tested, 3000);
  // Vertices and edge midpoints of the surface itself count as inside.
  EXPECT_TRUE(inside.inside(sphere.vertices.row(0).transpose()));
  EXPECT_TRUE(inside.intersects(Eigen::AlignedBox3d(Eigen::Vector3d(0.45, -0.05, -0.05), Eigen::Vector3d(0.55, 0.05, 0.05))));
  EXPECT_FALSE(inside.intersects(Eigen::AlignedBox3d(Eigen::Vector3d(-0.1, -0.1, -0.1), Eigen::Vector3d(0.1, 0.1, 0.1))));
}

TEST(Voxelize, VolumeConvergesToTheSurfaceVolume) {
  const TriangleSurface blob = read_triangle_surface(example("blob.off"));
  const InsideTest shape(blob);
  double previous_error = 1e300;
  for (int resolution : {8, 16, 32}) {
    VoxelizeOptions centre;
    centre.resolution = resolution;
    centre.keep_crossing = false;
    VoxelizeOptions cover = centre;
    cover.keep_crossing = true;
    const VolumeMesh c = voxelize_surface(shape, centre), k = voxelize_surface(shape, cover);
    validate_mesh(c, "centre"), validate_mesh(k, "cover");
    const double vc = lattice_volume(c), vk = lattice_volume(k);
    const double error = std::abs(vc - blob.volume()) / blob.volume();
    std::printf("  resolution %2d: centre cells %5ld volume %.5f (error %.2f%%), covering cells %5ld volume %.5f, surface %.5f\n",
                resolution, static_cast<long>(c.num_elements()), vc, 100 * error, static_cast<long>(k.num_elements()), vk,
                blob.volume());
    EXPECT_LT(error, previous_error);
    EXPECT_GE(vk, blob.volume());  // covering cells contain the solid
    EXPECT_GE(k.num_elements(), c.num_elements());
    previous_error = error;
  }
  EXPECT_LT(previous_error, 0.02);
}

TEST(Voxelize, CellSizeAlignsWithABoxAndRejectsBadOptions) {
  TempDir dir;
  const TriangleSurface cube = read_triangle_surface(dir.write("cube.obj",
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 0 0 2\nv 1 0 2\nv 0 1 2\nv 1 1 2\n"
      "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n"));
  const InsideTest shape(cube);
  VoxelizeOptions o;
  o.cell_size = 0.25;
  const VolumeMesh m = voxelize_surface(shape, o);
  EXPECT_EQ(m.num_elements(), 4 * 4 * 8);  // cells touching the faces from outside are not kept
  EXPECT_EQ(m.num_vertices(), 5 * 5 * 9);
  EXPECT_NEAR(lattice_volume(m), 2.0, 1e-12);
  VoxelizeOptions both = o;
  both.resolution = 3;
  EXPECT_THROW(voxelize_surface(shape, both), Error);
  VoxelizeOptions tiny;
  tiny.cell_size = 1e-5;
  EXPECT_THROW(voxelize_surface(shape, tiny), Error);
}

TEST(Voxelize, NonManifoldOptionSeparatesCubesTouchingAlongAnEdge) {
  const InsideTest cubes(read_triangle_surface(example("two_cubes_edge.obj")));
  VoxelizeOptions o;
  o.resolution = 4;  // h = 0.5: 8 cells per cube
  const VolumeMesh glued = voxelize_surface(cubes, o);
  o.non_manifold = true;
  const VolumeMesh split = voxelize_surface(cubes, o);
  ASSERT_EQ(glued.num_elements(), 16);
  ASSERT_EQ(split.num_elements(), 16);
  // Each cube has 27 lattice vertices; the edge x = y = 1 has 3 of them.
  EXPECT_EQ(glued.num_vertices(), 2 * 27 - 3);
  EXPECT_EQ(split.num_vertices(), 2 * 27);
  auto vertices_of = [](const VolumeMesh& m, bool first_cube) {
    std::set<int> vs;
    for (Eigen::Index e = 0; e < m.num_elements(); ++e) {
      const bool in_first = m.vertices(m.elements(e, 0), 0) < 1.0 - 1e-9;
      if (in_first == first_cube)
        for (int a = 0; a < 8; ++a) vs.insert(m.elements(e, a));
    }
    return vs;
  };
  for (const auto* m : {&glued, &split}) {
    const auto a = vertices_of(*m, true), b = vertices_of(*m, false);
    std::vector<int> common;
    std::set_intersection(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(common));
    EXPECT_EQ(common.size(), m == &glued ? 3u : 0u);
  }
}

// Each cube clamped at its far face, under gravity: split, cube A deforms exactly as when
// simulated alone; glued, the shared edge couples it to cube B.
TEST(Voxelize, NonManifoldCubesDoNotDragEachOther) {
  TempDir dir;
  const std::string cube_a = dir.write("a.obj",
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 0 0 1\nv 1 0 1\nv 0 1 1\nv 1 1 1\n"
      "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n").string();
  auto run = [&](const std::string& name, const std::string& surface, const std::string& size, bool non_manifold,
                 bool clamp_b) {
    const std::string scene = fmt::format(R"({{
      "mesh": {{"surface": "{}", {}, "non_manifold": {}}},
      "material": {{"family": "stable_neo_hookean", "E": 1e6, "nu": 0.3}},
      "density": 1000, "loads": {{"gravity": [0, 0, -9.81]}},
      "boundary": [{{"name": "a", "select": {{"plane": {{"point": [0, 0, 0], "normal": [-1, 0, 0]}}}}}}{}],
      "solver": {{"newton": {{"convergence": "absolute", "tolerance": 1e-9}}}},
      "output": {{"obj": false}}
    }})", surface, size, non_manifold ? "true" : "false",
        clamp_b ? R"(, {"name": "b", "select": {"plane": {"point": [2, 0, 0], "normal": [1, 0, 0]}}})" : "");
    RunOptions options;
    options.out_dir = dir / name;
    const RunSummary s = run_scene(load_scene(dir.write(name + ".json", scene)), options);
    EXPECT_TRUE(s.all_converged());
    return std::pair(read_volume_mesh(dir / name / "frame_0000.vtu"), read_volume_mesh(dir / name / "frame_0001.vtu"));
  };
  const auto [alone0, alone1] = run("alone", cube_a, R"("cell_size": 0.5)", false, false);
  // Displacement of cube A's vertices, keyed by rest position (the split mesh has two copies
  // of the edge vertices; the one in an element of cube A is taken).
  auto displacement_of_a = [](const VolumeMesh& rest, const VolumeMesh& deformed) {
    std::map<std::array<long, 3>, Eigen::Vector3d> u;
    for (Eigen::Index e = 0; e < rest.num_elements(); ++e) {
      if (rest.vertices(rest.elements(e, 0), 0) > 1.0 - 1e-9) continue;  // cube B
      for (int a = 0; a < 8; ++a) {
        const int v = rest.elements(e, a);
        const std::array<long, 3> key = {std::lround(4 * rest.vertices(v, 0)), std::lround(4 * rest.vertices(v, 1)),
                                         std::lround(4 * rest.vertices(v, 2))};
        u[key] = (deformed.vertices.row(v) - rest.vertices.row(v)).transpose();
      }
    }
    return u;
  };
  const auto reference = displacement_of_a(alone0, alone1);
  ASSERT_EQ(reference.size(), 27u);
  double max_u = 0.0;
  for (const auto& [k, d] : reference) max_u = std::max(max_u, d.norm());
  ASSERT_GT(max_u, 1e-4);
  for (bool non_manifold : {true, false}) {
    const auto [r0, r1] = run(non_manifold ? "split" : "glued", example("two_cubes_edge.obj").string(),
                              R"("resolution": 4)", non_manifold, true);
    const auto u = displacement_of_a(r0, r1);
    ASSERT_EQ(u.size(), 27u);
    double diff = 0.0;
    for (const auto& [k, d] : u) diff = std::max(diff, (d - reference.at(k)).norm());
    std::printf("  %s: max |u_A - u_A alone| = %.3g (max |u_A alone| = %.3g)\n", non_manifold ? "non-manifold" : "manifold",
                diff, max_u);
    if (non_manifold) {
      EXPECT_LT(diff, 1e-6 * max_u);
    } else {
      EXPECT_GT(diff, 0.05 * max_u);
    }
  }
}

}  // namespace
}  // namespace sinew
