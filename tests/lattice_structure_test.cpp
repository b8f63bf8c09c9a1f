// The grid a lattice was cut from survives meshing (VolumeMesh::lattice): for box, occupancy and
// voxelised lattices (with and without non-manifold vertex copies) every vertex sits at its grid
// point and every element's nodes at its cell's corners; splitting into tetrahedra drops it, a
// mismatched structure is rejected, and a scene's mesh and discretisation keep it.
#include <gtest/gtest.h>

#include <array>
#include <map>
#include <nlohmann/json.hpp>

#include "io_test_support.hpp"
#include "sinew/element/discretization.hpp"
#include "sinew/io/surface_reader.hpp"
#include "sinew/mesh/inside_test.hpp"
#include "sinew/mesh/lattice.hpp"
#include "sinew/mesh/voxelize.hpp"
#include "sinew/model/scene.hpp"

namespace sinew {
namespace {

using test::error_message;
using test::expect_contains;

std::filesystem::path meshes() { return std::filesystem::path(SINEW_EXAMPLES) / "meshes"; }

// Corner a of a cell (VTK_HEXAHEDRON order) as offsets along x, y, z.
const std::array<Eigen::Vector3i, 8> kCorner = {
    Eigen::Vector3i(0, 0, 0), Eigen::Vector3i(1, 0, 0), Eigen::Vector3i(1, 1, 0), Eigen::Vector3i(0, 1, 0),
    Eigen::Vector3i(0, 0, 1), Eigen::Vector3i(1, 0, 1), Eigen::Vector3i(1, 1, 1), Eigen::Vector3i(0, 1, 1)};

// Checks the structure against the mesh; returns the number of vertices on each grid point.
std::map<Eigen::Index, int> check_structure(const VolumeMesh& m) {
  std::map<Eigen::Index, int> copies;
  EXPECT_TRUE(m.lattice.has_value());
  if (!m.lattice) return copies;
  const LatticeStructure& g = *m.lattice;
  EXPECT_NO_THROW(m.validate("lattice"));
  const double tol = 1e-12 * (g.spacing.cwiseProduct(g.cells.cast<double>())).norm();
  for (Eigen::Index v = 0; v < m.num_vertices(); ++v) {
    const Eigen::Vector3i p = g.vertex_point.row(v).transpose();
    EXPECT_TRUE((p.array() >= 0).all() && (p.array() <= g.cells.array()).all()) << "vertex " << v;
    EXPECT_LE((m.vertices.row(v).transpose() - g.position(p)).norm(), tol) << "vertex " << v;
    ++copies[g.point_index(p)];
  }
  for (Eigen::Index e = 0; e < m.num_elements(); ++e) {
    const Eigen::Vector3i c = g.element_cell.row(e).transpose();
    EXPECT_TRUE((c.array() >= 0).all() && (c.array() < g.cells.array()).all()) << "element " << e;
    for (int a = 0; a < 8; ++a)
      EXPECT_EQ(Eigen::Vector3i(g.vertex_point.row(m.elements(e, a)).transpose()), c + kCorner[a])
          << "element " << e << " node " << a;
  }
  // Copies of one grid point are numbered 0, 1, ...
  std::map<Eigen::Index, std::vector<int>> numbers;
  for (Eigen::Index v = 0; v < m.num_vertices(); ++v)
    numbers[g.point_index(g.vertex_point.row(v).transpose())].push_back(g.vertex_copy(v));
  for (auto& [point, n] : numbers) {
    std::sort(n.begin(), n.end());
    for (size_t i = 0; i < n.size(); ++i) EXPECT_EQ(n[i], static_cast<int>(i)) << "grid point " << point;
  }
  return copies;
}

TEST(LatticeStructure, BoxAndOccupancyLatticesKeepTheirGrid) {
  const VolumeMesh box = box_lattice(Eigen::Vector3d(-1, 0, 2), Eigen::Vector3d(2, 1, 4), Eigen::Vector3i(3, 2, 4));
  ASSERT_TRUE(box.lattice);
  EXPECT_EQ(box.lattice->cells, Eigen::Vector3i(3, 2, 4));
  EXPECT_EQ(box.lattice->origin, Eigen::Vector3d(-1, 0, 2));
  EXPECT_TRUE(box.lattice->spacing.isApprox(Eigen::Vector3d(1, 0.5, 0.5)));
  EXPECT_FALSE(box.lattice->non_manifold);
  EXPECT_EQ(check_structure(box).size(), 4u * 3u * 5u);

  const SignedDistance ball = sphere_sdf(Eigen::Vector3d::Zero(), 1.0);
  const VolumeMesh sphere = occupancy_lattice(Eigen::AlignedBox3d(Eigen::Vector3d::Constant(-1), Eigen::Vector3d::Ones()),
                                              Eigen::Vector3i(6, 7, 8), [&](const Eigen::Vector3d& p) { return ball(p) <= 0; });
  ASSERT_TRUE(sphere.lattice);
  EXPECT_EQ(sphere.lattice->cells, Eigen::Vector3i(6, 7, 8));
  const auto copies = check_structure(sphere);
  EXPECT_EQ(static_cast<Eigen::Index>(copies.size()), sphere.num_vertices());  // one vertex per grid point

  EXPECT_FALSE(tetrahedralize_hexes(box).lattice.has_value());
  // The discretisation keeps the mesh's structure.
  EXPECT_EQ(Discretization(box).mesh().lattice->cells, Eigen::Vector3i(3, 2, 4));
}

TEST(LatticeStructure, SurvivesVoxelisation) {
  const InsideTest blob(read_triangle_surface(meshes() / "blob.off"));
  VoxelizeOptions o;
  o.resolution = 10;
  const VolumeMesh m = voxelize_surface(blob, o);
  ASSERT_TRUE(m.lattice);
  const LatticeStructure& g = *m.lattice;
  const double h = blob.bounds().sizes().maxCoeff() / 10;
  EXPECT_NEAR(g.spacing(0), h, 1e-14 * h);
  EXPECT_EQ(g.spacing, Eigen::Vector3d::Constant(g.spacing(0)));
  EXPECT_TRUE(g.origin.isApprox(blob.bounds().min()));
  for (int i = 0; i < 3; ++i) EXPECT_EQ(g.cells(i), static_cast<int>(std::ceil(blob.bounds().sizes()(i) / h - 1e-9)));
  EXPECT_EQ(g.cells.maxCoeff(), 10);
  EXPECT_EQ(static_cast<Eigen::Index>(check_structure(m).size()), m.num_vertices());
}

TEST(LatticeStructure, NumbersTheCopiesOfNonManifoldVertices) {
  const InsideTest cubes(read_triangle_surface(meshes() / "two_cubes_edge.obj"));
  VoxelizeOptions o;
  o.resolution = 4;  // two cubes of 8 cells touching along an edge with 3 grid points
  const VolumeMesh glued = voxelize_surface(cubes, o);
  o.non_manifold = true;
  const VolumeMesh split = voxelize_surface(cubes, o);
  ASSERT_TRUE(glued.lattice && split.lattice);
  EXPECT_FALSE(glued.lattice->non_manifold);
  EXPECT_TRUE(split.lattice->non_manifold);
  EXPECT_EQ(glued.lattice->cells, split.lattice->cells);
  const auto one = check_structure(glued), two = check_structure(split);
  EXPECT_EQ(one.size(), two.size());  // the same grid points
  int doubled = 0;
  for (const auto& [point, n] : two) {
    EXPECT_EQ(one.at(point), 1);
    EXPECT_LE(n, 2);
    doubled += n == 2;
  }
  EXPECT_EQ(doubled, 3);
  EXPECT_EQ(split.num_vertices(), glued.num_vertices() + 3);
}

TEST(LatticeStructure, AMismatchedStructureIsRejected) {
  const VolumeMesh m = box_lattice(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), Eigen::Vector3i(2, 2, 2));
  ASSERT_TRUE(m.lattice);
  LatticeStructure fewer = *m.lattice, outside = *m.lattice;
  fewer.vertex_point.conservativeResize(m.num_vertices() - 1, 3);
  expect_contains(error_message([&] { fewer.validate(m.num_vertices(), m.num_elements(), "m.vtu"); }),
                  {"m.vtu", "lists 26 vertices, the mesh has 27"});
  outside.element_cell(3, 1) = 2;
  VolumeMesh with_outside = m;
  with_outside.lattice = outside;
  expect_contains(error_message([&] { with_outside.validate("m.vtu"); }), {"element 3 lies outside the lattice grid"});
}

TEST(LatticeStructure, SceneMeshesKeepIt) {
  using nlohmann::json;
  const json material = {{"family", "stable_neo_hookean"}, {"E", 1e5}, {"nu", 0.3}};
  const Scene box = parse_scene({{"mesh", {{"box", {{"min", {0, 0, 0}}, {"max", {2, 1, 1}}}}, {"cells", {4, 2, 2}}}},
                                 {"material", material}},
                                "box.json");
  const VolumeMesh b = build_scene_mesh(box);
  ASSERT_TRUE(b.lattice);
  EXPECT_EQ(b.lattice->cells, Eigen::Vector3i(4, 2, 2));
  check_structure(b);
  const Scene voxels = parse_scene(
      {{"mesh", {{"surface", "two_cubes_edge.obj"}, {"resolution", 4}, {"non_manifold", true}}}, {"material", material}},
      meshes() / "s.json");
  const VolumeMesh v = build_scene_mesh(voxels);
  ASSERT_TRUE(v.lattice);
  EXPECT_TRUE(v.lattice->non_manifold);
  check_structure(v);
  const Scene tets = parse_scene({{"mesh", {{"surface", "two_cubes_edge.obj"}, {"resolution", 2}, {"element", "tet"}}},
                                  {"material", material}},
                                 meshes() / "s.json");
  EXPECT_FALSE(build_scene_mesh(tets).lattice.has_value());
}

}  // namespace
}  // namespace sinew
