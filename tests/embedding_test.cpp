// Embedding of surface points in hexahedral and tetrahedral meshes: the weights reproduce the
// points at rest and under any affine map of the mesh exactly; points outside extrapolate.
// Tetrahedralisation through Gmsh keeps the surface as the mesh boundary (same volume).
#include <gtest/gtest.h>

#include <numbers>

#include "io_test_support.hpp"
#include "sinew/element/mesh_validation.hpp"
#include "sinew/element/embedding.hpp"
#include "sinew/io/surface_reader.hpp"
#include "sinew/mesh/inside_test.hpp"
#include "sinew/mesh/lattice.hpp"
#include "sinew/mesh/surface.hpp"
#include "sinew/mesh/tetrahedralize_surface.hpp"
#include "sinew/mesh/voxelize.hpp"

namespace sinew {
namespace {

std::filesystem::path example(const std::string& name) { return std::filesystem::path(SINEW_EXAMPLES) / "meshes" / name; }

Eigen::VectorXd affine_positions(const VolumeMesh& mesh, const Eigen::Matrix3d& A, const Eigen::Vector3d& b) {
  Eigen::VectorXd x(3 * mesh.num_vertices());
  for (Eigen::Index v = 0; v < mesh.num_vertices(); ++v) x.segment<3>(3 * v) = A * mesh.vertices.row(v).transpose() + b;
  return x;
}

void expect_reproduces(const VolumeMesh& mesh, const Eigen::MatrixX3d& points, double tol) {
  const Embedding emb = embed_points(mesh, points);
  ASSERT_EQ(emb.num_points(), points.rows());
  EXPECT_LT((emb.positions(mesh.rest_positions()) - points).cwiseAbs().maxCoeff(), tol);
  for (Eigen::Index p = 0; p < points.rows(); ++p) EXPECT_NEAR(emb.weights.row(p).sum(), 1.0, 1e-13);
  Eigen::Matrix3d A;
  A << 1.2, 0.3, -0.1, 0.05, 0.9, 0.2, -0.3, 0.1, 1.1;
  const Eigen::Vector3d b(0.4, -1.0, 2.0);
  const Eigen::MatrixX3d expected = (points * A.transpose()).rowwise() + b.transpose();
  EXPECT_LT((emb.positions(affine_positions(mesh, A, b)) - expected).cwiseAbs().maxCoeff(), tol);
}

TEST(Embedding, ReproducesPointsAtRestAndUnderAffineMapsInHexesAndTets) {
  const TriangleSurface torus = read_triangle_surface(example("torus.obj"));
  VoxelizeOptions o;
  o.resolution = 10;
  const VolumeMesh hexes = voxelize_surface(InsideTest(torus), o);
  expect_reproduces(hexes, torus.vertices, 1e-13);
  EXPECT_LT(embed_points(hexes, torus.vertices).max_outside, 1e-12);  // covering cells hold every surface vertex
  expect_reproduces(tetrahedralize_hexes(hexes), torus.vertices, 1e-13);
  // A distorted (non-affine) hexahedral mesh: the trilinear map is inverted by Newton.
  VolumeMesh bent = box_lattice(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), Eigen::Vector3i(3, 3, 3));
  for (Eigen::Index v = 0; v < bent.num_vertices(); ++v) {
    const Eigen::Vector3d X = bent.vertices.row(v);
    bent.vertices.row(v) += 0.08 * Eigen::RowVector3d(std::sin(3 * X.y()), X.x() * X.z(), std::cos(2 * X.x()) * X.y());
  }
  validate_mesh(bent, "bent");
  Eigen::MatrixX3d inside(50, 3);
  for (int p = 0; p < 50; ++p) {
    // Mesh points at known reference coordinates of element p % 27: exact by construction.
    const Eigen::Index e = p % bent.num_elements();
    const Eigen::Vector3d xi(std::sin(p), std::cos(1.3 * p), 0.9 * std::sin(0.7 * p + 1));
    Eigen::Matrix<double, 8, 3> X;
    for (int a = 0; a < 8; ++a) X.row(a) = bent.vertices.row(bent.elements(e, a));
    Eigen::Matrix<double, 8, 1> N;
    const int corner[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1}, {-1, -1, 1}, {1, -1, 1}, {1, 1, 1}, {-1, 1, 1}};
    for (int a = 0; a < 8; ++a)
      N(a) = 0.125 * (1 + corner[a][0] * xi.x()) * (1 + corner[a][1] * xi.y()) * (1 + corner[a][2] * xi.z());
    inside.row(p) = (X.transpose() * N).transpose();
  }
  expect_reproduces(bent, inside, 1e-12);
}

TEST(Embedding, PointsOutsideTheMeshBindToTheNearestElement) {
  const VolumeMesh cube = box_lattice(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), Eigen::Vector3i(2, 2, 2));
  Eigen::MatrixX3d points(2, 3);
  points << 1.1, 0.5, 0.5, -0.05, -0.05, 0.25;
  const Embedding emb = embed_points(cube, points);
  EXPECT_NEAR(emb.max_outside, 0.4, 1e-12);  // 0.1 beyond a cell of size 0.5 (reference size 2): 0.4
  expect_reproduces(cube, points, 1e-13);
}

TEST(Tetrahedralize, GmshKeepsTheSurfaceAsTheBoundary) {
  const TriangleSurface blob = read_triangle_surface(example("blob.off"));
  Eigen::Index previous = 0;
  for (double max_edge : {0.2, 0.03}) {  // the surface's edges are about 0.05 long
    const VolumeMesh tets = tetrahedralize_surface(blob, max_edge);
    double volume = 0.0;
    for (Eigen::Index e = 0; e < tets.num_elements(); ++e) {
      Eigen::Matrix3d D;
      for (int i = 0; i < 3; ++i) D.col(i) = (tets.vertices.row(tets.elements(e, i + 1)) - tets.vertices.row(tets.elements(e, 0))).transpose();
      volume += D.determinant() / 6.0;
    }
    std::printf("  max_edge %.2f: %ld tetrahedra, %ld vertices, volume %.6f (surface %.6f)\n", max_edge,
                static_cast<long>(tets.num_elements()), static_cast<long>(tets.num_vertices()), volume, blob.volume());
    EXPECT_NEAR(volume, blob.volume(), 1e-9 * blob.volume());
    EXPECT_GT(tets.num_elements(), previous);  // a smaller max_edge refines the inside
    previous = tets.num_elements();
    EXPECT_EQ(boundary_surface(tets).triangles.rows(), blob.num_faces());
    const Embedding emb = embed_points(tets, blob.vertices);
    EXPECT_LT(emb.max_outside, 1e-9);
    EXPECT_LT((emb.positions(tets.rest_positions()) - blob.vertices).cwiseAbs().maxCoeff(), 1e-12);
  }
  // Not closed: rejected before Gmsh is called.
  TriangleSurface open = blob;
  open.faces.conservativeResize(open.num_faces() - 1, 3);
  EXPECT_THROW(tetrahedralize_surface(open, 0.1), Error);
  EXPECT_THROW(tetrahedralize_surface(blob, -1.0), Error);
}

}  // namespace
}  // namespace sinew
