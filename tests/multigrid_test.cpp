// Geometric multigrid on lattices: the coarsened lattices interpolate linear functions exactly
// (partially filled coarse cells included), keep non-manifold copies apart and merge corners
// shared through a face; the Galerkin product equals the explicit triple product P^T A P over
// the free DOFs, from an assembled matrix or summed over element matrices (matrix-free); the
// V-cycle is a symmetric positive definite preconditioner; PCG's iteration count stays bounded as
// the lattice grows at nu = 0.49, where block-Jacobi's grows; and a matrix-free operator gets the
// same V-cycle as the assembled one.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cstdio>
#include <map>
#include <random>

#include "elastic_bar_support.hpp"
#include "io_test_support.hpp"
#include "spd_test_support.hpp"
#include "sinew/assembly/problem.hpp"
#include "sinew/forms/elastic_form.hpp"
#include "sinew/linalg/block_hessian.hpp"
#include "sinew/linalg/element_galerkin.hpp"
#include "sinew/linalg/galerkin_product.hpp"
#include "sinew/material/families/corotational.hpp"
#include "sinew/mesh/lattice.hpp"
#include "sinew/mesh/selection.hpp"
#include "sinew/solver/lattice_hierarchy.hpp"
#include "sinew/solver/multigrid_preconditioner.hpp"
#include "sinew/solver/pcg_solver.hpp"

namespace sinew {
namespace {

using test::error_message;
using test::expect_contains;

// P applied to a function given at the coarse vertices, evaluated at fine vertex v.
Eigen::Vector3d interpolate(const VertexInterpolation& P, int v, const std::vector<Eigen::Vector3d>& coarse) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int k = P.offsets[static_cast<size_t>(v)]; k < P.offsets[static_cast<size_t>(v) + 1]; ++k)
    sum += P.weight[static_cast<size_t>(k)] * coarse[static_cast<size_t>(P.coarse[static_cast<size_t>(k)])];
  return sum;
}

// The coarse level's grid points in fine grid units: interpolating them must give each fine
// vertex its own grid point (trilinear interpolation is exact for linear functions).
void expect_linear_exactness(const LatticeLevel& fine, const LatticeLevel& coarse, const VertexInterpolation& P) {
  std::vector<Eigen::Vector3d> position(coarse.vertex_point.size());
  for (size_t c = 0; c < position.size(); ++c) position[c] = 2.0 * coarse.vertex_point[c].cast<double>();
  ASSERT_EQ(P.fine_vertices(), fine.vertices());
  for (int v = 0; v < fine.vertices(); ++v) {
    double sum = 0.0;
    for (int k = P.offsets[static_cast<size_t>(v)]; k < P.offsets[static_cast<size_t>(v) + 1]; ++k) sum += P.weight[static_cast<size_t>(k)];
    EXPECT_NEAR(sum, 1.0, 1e-14) << "vertex " << v;
    EXPECT_LE((interpolate(P, v, position) - fine.vertex_point[static_cast<size_t>(v)].cast<double>()).norm(), 1e-12)
        << "vertex " << v;
  }
}

TEST(LatticeHierarchy, BoxCoarsensByTwoAndInterpolatesLinearFunctions) {
  // 5 x 4 x 3 cells: the last coarse layer along x and z is half filled.
  const VolumeMesh box = box_lattice(Eigen::Vector3d::Zero(), Eigen::Vector3d(5, 4, 3), Eigen::Vector3i(5, 4, 3));
  const LatticeLevel fine = lattice_level(box);
  VertexInterpolation P;
  const LatticeLevel coarse = coarsen(fine, P);
  EXPECT_EQ(coarse.cell.size(), 3u * 2u * 2u);
  EXPECT_EQ(coarse.vertices(), 4 * 3 * 3);
  expect_linear_exactness(fine, coarse, P);
  VertexInterpolation P2;
  const LatticeLevel coarser = coarsen(coarse, P2);
  EXPECT_EQ(coarser.cell.size(), 2u * 1u * 1u);
  EXPECT_EQ(coarser.vertices(), 3 * 2 * 2);
  expect_linear_exactness(coarse, coarser, P2);
  // The hierarchy stops at the vertex budget.
  const LatticeHierarchy h = lattice_hierarchy(box, 40, 10);
  ASSERT_EQ(h.levels.size(), 2u);
  EXPECT_EQ(h.levels[1].vertices(), 36);
  EXPECT_EQ(lattice_hierarchy(box, 1, 10).levels.size(), 4u);  // down to a single coarse cell
  EXPECT_EQ(lattice_hierarchy(box, 1, 10).levels.back().vertices(), 8);
}

// Two cells of one coarse cell that touch along the edge x = y = 1, with that edge's two
// vertices shared (`glued`) or duplicated (non-manifold copies).
VolumeMesh edge_pair(bool glued) {
  VolumeMesh m;
  LatticeStructure g;
  g.cells = Eigen::Vector3i(2, 2, 1);
  g.spacing = Eigen::Vector3d::Ones();
  g.non_manifold = !glued;
  const std::array<Eigen::Vector3i, 8> corner = {Eigen::Vector3i(0, 0, 0), Eigen::Vector3i(1, 0, 0), Eigen::Vector3i(1, 1, 0),
                                                 Eigen::Vector3i(0, 1, 0), Eigen::Vector3i(0, 0, 1), Eigen::Vector3i(1, 0, 1),
                                                 Eigen::Vector3i(1, 1, 1), Eigen::Vector3i(0, 1, 1)};
  std::vector<Eigen::Vector3i> points;
  std::vector<int> copies;
  std::map<std::array<int, 4>, int> index;
  m.elements.resize(2, 8);
  g.element_cell.resize(2, 3);
  const Eigen::Vector3i cells[2] = {Eigen::Vector3i(0, 0, 0), Eigen::Vector3i(1, 1, 0)};
  for (int e = 0; e < 2; ++e) {
    g.element_cell.row(e) = cells[e].transpose();
    for (int a = 0; a < 8; ++a) {
      const Eigen::Vector3i p = cells[e] + corner[static_cast<size_t>(a)];
      const int copy = (!glued && e == 1 && p(0) == 1 && p(1) == 1) ? 1 : 0;
      const std::array<int, 4> key{p(0), p(1), p(2), copy};
      auto [it, added] = index.emplace(key, static_cast<int>(points.size()));
      if (added) {
        points.push_back(p);
        copies.push_back(copy);
      }
      m.elements(e, a) = it->second;
    }
  }
  m.vertices.resize(static_cast<Eigen::Index>(points.size()), 3);
  g.vertex_point.resize(static_cast<Eigen::Index>(points.size()), 3);
  g.vertex_copy.resize(static_cast<Eigen::Index>(points.size()));
  for (size_t v = 0; v < points.size(); ++v) {
    m.vertices.row(static_cast<Eigen::Index>(v)) = points[v].cast<double>().transpose();
    g.vertex_point.row(static_cast<Eigen::Index>(v)) = points[v].transpose();
    g.vertex_copy(static_cast<Eigen::Index>(v)) = copies[v];
  }
  m.lattice = g;
  m.validate("edge pair");
  return m;
}

TEST(LatticeHierarchy, NonManifoldCopiesGetCoarseCellsOfTheirOwn) {
  const VolumeMesh split = edge_pair(false), glued = edge_pair(true);
  EXPECT_EQ(split.num_vertices(), glued.num_vertices() + 2);
  VertexInterpolation Ps, Pg;
  const LatticeLevel fs = lattice_level(split), fg = lattice_level(glued);
  const LatticeLevel cs = coarsen(fs, Ps), cg = coarsen(fg, Pg);
  EXPECT_EQ(cs.cell.size(), 2u);  // one coarse cell per copy
  EXPECT_EQ(cs.vertices(), 16);
  EXPECT_EQ(cg.cell.size(), 1u);
  EXPECT_EQ(cg.vertices(), 8);
  expect_linear_exactness(fs, cs, Ps);
  expect_linear_exactness(fg, cg, Pg);
  // No coarse vertex of the split pair interpolates to both cells.
  std::vector<int> owner(16, -1);
  for (int e = 0; e < 2; ++e)
    for (int v : fs.corners[static_cast<size_t>(e)])
      for (int k = Ps.offsets[static_cast<size_t>(v)]; k < Ps.offsets[static_cast<size_t>(v) + 1]; ++k) {
        int& o = owner[static_cast<size_t>(Ps.coarse[static_cast<size_t>(k)])];
        EXPECT_TRUE(o < 0 || o == e);
        o = e;
      }
}

TEST(LatticeHierarchy, CellsJoinedThroughAFaceShareCoarseCorners) {
  // Cells 1 and 2 along x lie in different coarse cells and share the face x = 2.
  const VolumeMesh bar = occupancy_lattice(Eigen::AlignedBox3d(Eigen::Vector3d::Zero(), Eigen::Vector3d(4, 1, 1)),
                                           Eigen::Vector3i(4, 1, 1), [](const Eigen::Vector3d& c) { return c.x() > 1 && c.x() < 3; });
  ASSERT_EQ(bar.num_elements(), 2);
  VertexInterpolation P;
  const LatticeLevel fine = lattice_level(bar);
  const LatticeLevel coarse = coarsen(fine, P);
  EXPECT_EQ(coarse.cell.size(), 2u);
  EXPECT_EQ(coarse.vertices(), 12);  // 2 x 8 corners, the 4 on the shared face once
  expect_linear_exactness(fine, coarse, P);
}

TEST(LatticeHierarchy, RejectsMeshesWithoutALattice) {
  VolumeMesh m = box_lattice(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), Eigen::Vector3i(2, 2, 2));
  m.lattice.reset();
  expect_contains(error_message([&] { lattice_level(m); }), {"multigrid", "no lattice grid"});
}

// The Hessian of a linear co-rotational hexahedral lattice at rest (tests/elastic_bar_support.hpp),
// the vertices up to `pinned_height` pinned, one DOF of the top face fixed on its own (a partly
// fixed vertex).
struct Bar : test::ElasticBar {
  Bar(const Eigen::Vector3i& cells, double nu, double pinned_height = 0.0) : ElasticBar(cells, nu, false, pinned_height) {
    const std::vector<int> top =
        select_vertices(disc->mesh().vertices, PlaneSelector{{0, 0, static_cast<double>(cells(2))}, {0, 0, 1}}, "top");
    fix(3 * top.front() + 1);
  }
};

// P with fixed fine DOFs dropped, as a scalar sparse matrix.
Eigen::SparseMatrix<double> masked_interpolation(const VertexInterpolation& P, const std::vector<char>& free) {
  std::vector<Eigen::Triplet<double>> t;
  for (int v = 0; v < P.fine_vertices(); ++v)
    for (int k = P.offsets[static_cast<size_t>(v)]; k < P.offsets[static_cast<size_t>(v) + 1]; ++k)
      for (int i = 0; i < 3; ++i)
        if (free[static_cast<size_t>(3 * v + i)])
          t.emplace_back(3 * v + i, 3 * P.coarse[static_cast<size_t>(k)] + i, P.weight[static_cast<size_t>(k)]);
  Eigen::SparseMatrix<double> M(3 * P.fine_vertices(), 3 * P.coarse_vertices);
  M.setFromTriplets(t.begin(), t.end());
  return M;
}

Eigen::MatrixXd dense(const BlockSparseMatrix& C) {
  Eigen::MatrixXd D = Eigen::MatrixXd::Zero(C.rows(), C.rows());
  for (int r = 0; r < static_cast<int>(C.block_rows()); ++r)
    for (int k = C.row_begin(r); k < C.row_end(r); ++k) D.block<3, 3>(3 * r, 3 * C.column(k)) = C.block(k);
  return D;
}

TEST(GalerkinProduct, EqualsTheExplicitTripleProductOverTheFreeDofs) {
  Bar bar(Eigen::Vector3i(5, 4, 3), 0.45, 1.0);  // two layers pinned: coarse vertices at z = 0 have no free DOF
  const Eigen::SparseMatrix<double>& A = *bar.problem->hessian(bar.x).matrix();
  const LatticeHierarchy h = lattice_hierarchy(bar.disc->mesh(), 1, 3);
  ASSERT_EQ(h.levels.size(), 3u);
  std::vector<char> free0(bar.fixed.size());
  for (size_t i = 0; i < free0.size(); ++i) free0[i] = bar.fixed[i] ? 0 : 1;
  const VertexInterpolation& P0 = h.interpolations[0];
  const std::vector<char> free1 = P0.coarse_free(free0);
  const GalerkinProduct g0(block_pattern(A), P0);
  EXPECT_GT(g0.colors(), 1);
  BlockSparseMatrix C1 = g0.make_coarse();
  g0.compute(A, free0, free1, C1);
  const Eigen::SparseMatrix<double> M0 = masked_interpolation(P0, free0);
  Eigen::MatrixXd expected = Eigen::MatrixXd(M0.transpose() * A * M0);
  int identity_rows = 0;
  for (Eigen::Index i = 0; i < expected.rows(); ++i)
    if (!free1[static_cast<size_t>(i)]) {
      expected(i, i) = 1.0;
      ++identity_rows;
    }
  EXPECT_GT(identity_rows, 0);  // coarse DOFs on the pinned face only
  EXPECT_LE((dense(C1) - expected).norm(), 1e-12 * expected.norm());
  EXPECT_LE((dense(C1) - dense(C1).transpose()).norm(), 1e-12 * expected.norm());

  // The next level from the block matrix, the same way.
  const VertexInterpolation& P1 = h.interpolations[1];
  const std::vector<char> free2 = P1.coarse_free(free1);
  const GalerkinProduct g1(block_pattern(C1), P1);
  BlockSparseMatrix C2 = g1.make_coarse();
  g1.compute(C1, free1, free2, C2);
  const Eigen::SparseMatrix<double> M1 = masked_interpolation(P1, free1);
  Eigen::MatrixXd expected2 = M1.transpose() * dense(C1) * M1;
  for (Eigen::Index i = 0; i < expected2.rows(); ++i)
    if (!free2[static_cast<size_t>(i)]) expected2(i, i) = 1.0;
  EXPECT_LE((dense(C2) - expected2).norm(), 1e-12 * expected2.norm());
  // The block product agrees with the scalar one.
  const Eigen::VectorXd u = Eigen::VectorXd::LinSpaced(C2.rows(), -1.0, 2.0);
  Eigen::VectorXd y;
  C2.apply(u, y);
  EXPECT_LE((y - expected2 * u).norm(), 1e-12 * (expected2 * u).norm());
}

// The bar's lattice coarsened once, with its fixed DOFs masked out on both levels.
struct OneCoarsening {
  LatticeHierarchy h;
  std::vector<char> free0, free1;
  explicit OneCoarsening(const Bar& bar) : h(lattice_hierarchy(bar.disc->mesh(), 1, 2)), free0(bar.fixed.size()) {
    for (size_t i = 0; i < free0.size(); ++i) free0[i] = bar.fixed[i] ? 0 : 1;
    free1 = P().coarse_free(free0);
  }
  const VertexInterpolation& P() const { return h.interpolations[0]; }
};

// A matrix whose vertex columns are not full 3x3 blocks (as a caller's own sparse matrix may be)
// takes the general reading of its columns and gives the same product. Column 3b + 2 (vertex b)
// loses an entry of vertex a's block and gains one of the last vertex's: its three columns keep
// equal lengths, but their rows no longer come in whole blocks.
TEST(GalerkinProduct, MatricesWithoutFullBlocksGiveTheTripleProductToo) {
  Bar bar(Eigen::Vector3i(5, 4, 3), 0.45, 1.0);
  const Eigen::SparseMatrix<double>& H = *bar.problem->hessian(bar.x).matrix();
  const int a = 70, b = 71;  // neighbours above the two pinned layers (6 x 5 vertices each)
  const int r = 3 * a + 1, c = 3 * b + 2;
  ASSERT_FALSE(bar.fixed[static_cast<size_t>(r)] || bar.fixed[static_cast<size_t>(c)]);
  const int last = static_cast<int>(H.rows()) - 3;  // first DOF of the last vertex, not coupled to b
  std::vector<Eigen::Triplet<double>> t = {{last, c, 0.5}, {c, last, 0.5}};
  int dropped = 0;
  for (int col = 0; col < H.outerSize(); ++col)
    for (Eigen::SparseMatrix<double>::InnerIterator it(H, col); it; ++it) {
      const bool drop = (it.row() == r && col == c) || (it.row() == c && col == r);
      dropped += drop ? 1 : 0;
      if (!drop) t.emplace_back(static_cast<int>(it.row()), col, it.value());
      EXPECT_FALSE((it.row() == last && col == c) || (it.row() == c && col == last));
    }
  ASSERT_EQ(dropped, 2);
  Eigen::SparseMatrix<double> A(H.rows(), H.cols());
  A.setFromTriplets(t.begin(), t.end());
  const OneCoarsening level(bar);
  const VertexInterpolation& P0 = level.P();
  const std::vector<char>&free0 = level.free0, &free1 = level.free1;
  const GalerkinProduct g(block_pattern(A), P0);
  BlockSparseMatrix C = g.make_coarse();
  g.compute(A, free0, free1, C);
  const Eigen::SparseMatrix<double> M = masked_interpolation(P0, free0);
  Eigen::MatrixXd expected = Eigen::MatrixXd(M.transpose() * A * M);
  for (Eigen::Index i = 0; i < expected.rows(); ++i)
    if (!free1[static_cast<size_t>(i)]) expected(i, i) = 1.0;
  EXPECT_LE((dense(C) - expected).norm(), 1e-12 * expected.norm());
}

// A lattice large enough that the rows (A P)_a kept for reuse are replaced while a task runs
// (more than 2048 fine vertices per task): still the triple product.
TEST(GalerkinProduct, LargeLatticesGiveTheTripleProduct) {
  Bar bar(Eigen::Vector3i(24, 20, 16), 0.45, 1.0);
  const Eigen::SparseMatrix<double>& A = *bar.problem->hessian(bar.x).matrix();
  const OneCoarsening level(bar);
  const VertexInterpolation& P0 = level.P();
  const std::vector<char>&free0 = level.free0, &free1 = level.free1;
  const GalerkinProduct g(block_pattern(A), P0);
  BlockSparseMatrix C = g.make_coarse();
  tbb::global_control one_task(tbb::global_control::max_allowed_parallelism, 1);
  g.compute(A, free0, free1, C);
  const Eigen::SparseMatrix<double> M = masked_interpolation(P0, free0);
  Eigen::SparseMatrix<double> expected = M.transpose() * A * M;
  double error = 0.0, norm = 0.0;
  for (int r = 0; r < static_cast<int>(C.block_rows()); ++r)
    for (int k = C.row_begin(r); k < C.row_end(r); ++k)
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
          const int row = 3 * r + i, col = 3 * C.column(k) + j;
          const double want = free1[static_cast<size_t>(row)] ? expected.coeff(row, col) : (row == col ? 1.0 : 0.0);
          error = std::max(error, std::abs(C.block(k)(i, j) - want));
          norm = std::max(norm, std::abs(want));
        }
  EXPECT_GT(norm, 0.0);
  EXPECT_LE(error, 1e-12 * norm);
}

// Rows of C are summed in parallel, each in a fixed order: the same bits with one thread or two.
TEST(GalerkinProduct, IsBitwiseTheSameWithOneThreadOrTwo) {
  Bar bar(Eigen::Vector3i(9, 8, 7), 0.45, 1.0);
  const Eigen::SparseMatrix<double>& A = *bar.problem->hessian(bar.x).matrix();
  const OneCoarsening level(bar);
  const VertexInterpolation& P0 = level.P();
  const std::vector<char>&free0 = level.free0, &free1 = level.free1;
  const GalerkinProduct g(block_pattern(A), P0);
  auto product = [&](int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    BlockSparseMatrix C = g.make_coarse();
    g.compute(A, free0, free1, C);
    return dense(C);
  };
  const Eigen::MatrixXd one = product(1), two = product(2);
  EXPECT_GT(one.norm(), 0.0);
  EXPECT_TRUE(one == two);
}

// Random symmetric element matrices on a mesh's hexahedra plus a few two-vertex couplings
// (springs between vertices of different elements), kept in double, and their assembled sum.
class RandomElements final : public ElementMatrices {
 public:
  explicit RandomElements(const VolumeMesh& mesh) {
    std::mt19937 rng(17);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (Eigen::Index e = 0; e < mesh.num_elements(); ++e) {
      std::vector<int> v(8);
      for (int a = 0; a < 8; ++a) v[static_cast<size_t>(a)] = mesh.elements(e, a);
      add(v, rng, u);
    }
    const int n = static_cast<int>(mesh.num_vertices());
    for (int k = 0; k < 5; ++k) add({(7 * k) % n, (13 * k + n / 2) % n}, rng, u);
    add({3}, rng, u);
  }
  Eigen::Index count() const override { return static_cast<Eigen::Index>(vertices_.size()); }
  int vertices(Eigen::Index e, int* v) const override {
    const auto& list = vertices_[static_cast<size_t>(e)];
    std::copy(list.begin(), list.end(), v);
    return static_cast<int>(list.size());
  }
  void matrix(Eigen::Index e, ElementMatrix& K) const override {
    const Eigen::MatrixXd& M = matrices_[static_cast<size_t>(e)];
    K.topLeftCorner(M.rows(), M.cols()) = M;
  }
  std::uint64_t structure_id() const override { return 42; }
  Eigen::SparseMatrix<double> assembled(Eigen::Index vertices) const {
    std::vector<Eigen::Triplet<double>> t;
    for (size_t e = 0; e < vertices_.size(); ++e)
      for (size_t a = 0; a < vertices_[e].size(); ++a)
        for (size_t b = 0; b < vertices_[e].size(); ++b)
          for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
              t.emplace_back(3 * vertices_[e][a] + i, 3 * vertices_[e][b] + j, matrices_[e](3 * a + i, 3 * b + j));
    Eigen::SparseMatrix<double> A(3 * vertices, 3 * vertices);
    A.setFromTriplets(t.begin(), t.end());
    return A;
  }

 private:
  void add(std::vector<int> v, std::mt19937& rng, std::uniform_real_distribution<double>& u) {
    const Eigen::Index n = 3 * static_cast<Eigen::Index>(v.size());
    Eigen::MatrixXd B(n, n);
    for (Eigen::Index i = 0; i < B.size(); ++i) B.data()[i] = u(rng);
    matrices_.push_back(B.transpose() * B);
    vertices_.push_back(std::move(v));
  }
  std::vector<std::vector<int>> vertices_;
  std::vector<Eigen::MatrixXd> matrices_;
};

// The element-wise product gives what the assembled one gives (partially filled coarse cells:
// 5 x 4 x 3 cells; fixed DOFs; couplings outside the elements).
TEST(ElementGalerkin, EqualsTheGalerkinProductOfTheAssembledMatrix) {
  Bar bar(Eigen::Vector3i(5, 4, 3), 0.45, 1.0);
  const VolumeMesh& mesh = bar.disc->mesh();
  const RandomElements elements(mesh);
  const Eigen::SparseMatrix<double> A = elements.assembled(mesh.num_vertices());
  const LatticeHierarchy h = lattice_hierarchy(mesh, 1, 2);
  ASSERT_EQ(h.levels.size(), 2u);
  std::vector<char> free0(bar.fixed.size());
  for (size_t i = 0; i < free0.size(); ++i) free0[i] = bar.fixed[i] ? 0 : 1;
  const VertexInterpolation& P = h.interpolations[0];
  const std::vector<char> free1 = P.coarse_free(free0);
  const GalerkinProduct assembled(block_pattern(A), P);
  BlockSparseMatrix expected = assembled.make_coarse();
  assembled.compute(A, free0, free1, expected);
  const ElementGalerkin by_elements(elements, P);
  EXPECT_GE(by_elements.colors(), 8);  // neighbouring coarse cells (the groups of elements) share corners
  BlockSparseMatrix C = by_elements.make_coarse();
  by_elements.compute(elements, free0, free1, C);
  const Eigen::MatrixXd D = dense(expected);
  EXPECT_LE((dense(C) - D).norm(), 1e-12 * D.norm());
  EXPECT_EQ(block_pattern(C), block_pattern(expected));
  // Computed again (Newton's next matrix): the same, not accumulated.
  by_elements.compute(elements, free0, free1, C);
  EXPECT_LE((dense(C) - D).norm(), 1e-12 * D.norm());
}

// A matrix-free Newton operator gets the same V-cycle: its element matrices (single precision)
// give the assembled coarse levels to ~1e-7 and PCG needs the same iterations. The solutions
// differ by what single precision does to the operator itself (~1e-7 relative, times the
// condition number at nu = 0.49: 1.2e-4 here), not by the preconditioner.
TEST(MultigridPreconditioner, WorksOnAMatrixFreeOperator) {
  Bar bar(Eigen::Vector3i(6, 6, 12), 0.49);
  const Eigen::VectorXd b = bar.rhs();
  MultigridSettings settings;
  settings.coarsest_dofs = 100;
  PcgSolver assembled_pcg(std::make_unique<MultigridPreconditioner>(settings), 500);
  PcgSolver free_pcg(std::make_unique<MultigridPreconditioner>(settings), 500);
  Eigen::VectorXd x_assembled, x_free;
  const LinearSolveReport ra = assembled_pcg.solve(bar.problem->hessian(bar.x), b, x_assembled, 1e-8, bar.context());
  bar.problem->set_matrix_free(true);
  const LinearOperator& H = bar.problem->hessian(bar.x);
  ASSERT_EQ(H.matrix(), nullptr);
  ASSERT_NE(H.element_matrices(), nullptr);
  const LinearSolveReport rf = free_pcg.solve(H, b, x_free, 1e-8, bar.context());
  auto& M = dynamic_cast<MultigridPreconditioner&>(free_pcg.preconditioner());
  EXPECT_GE(M.levels(), 3);
  EXPECT_EQ(M.levels(), dynamic_cast<MultigridPreconditioner&>(assembled_pcg.preconditioner()).levels());
  ASSERT_TRUE(ra.converged && rf.converged);
  std::printf("multigrid PCG to 1e-8: assembled %d, matrix-free %d iterations\n", ra.iterations, rf.iterations);
  EXPECT_LE(std::abs(ra.iterations - rf.iterations), 2);
  EXPECT_LE((x_free - x_assembled).norm(), 1e-3 * x_assembled.norm());
  test::expect_symmetric_positive(M, b, bar.fixed, 0.0, 1e-5);  // (single-precision fine products)
  // The next Newton matrix reuses the symbolic product (same elements).
  const LinearOperator& H2 = bar.problem->hessian(bar.x);
  EXPECT_TRUE(free_pcg.solve(H2, b, x_free, 1e-8, bar.context()).converged);
}

TEST(MultigridPreconditioner, IsSymmetricPositiveDefinite) {
  Bar bar(Eigen::Vector3i(6, 5, 7), 0.49);
  const LinearOperator& H = bar.problem->hessian(bar.x);
  MultigridSettings settings;
  settings.coarsest_dofs = 30;  // several levels on a small lattice
  MultigridPreconditioner M(settings);
  M.setup(H, bar.context());
  EXPECT_GE(M.levels(), 3);
  test::expect_symmetric_positive(M, bar.rhs(), bar.fixed);  // fixed DOFs exactly zero
}

TEST(MultigridPreconditioner, IterationsStayBoundedAsTheLatticeGrows) {
  // nu = 0.49, each size twice the last: multigrid's PCG iterations barely change while
  // block-Jacobi's grow with the mesh.
  std::vector<int> mg, bj;
  for (int n : {4, 8, 16}) {
    Bar bar(Eigen::Vector3i(n, n, 2 * n), 0.49);
    const LinearOperator& H = bar.problem->hessian(bar.x);
    const Eigen::VectorXd b = bar.rhs();
    MultigridSettings settings;
    settings.coarsest_dofs = 200;  // at least two levels at every size
    PcgSolver pcg_mg(std::make_unique<MultigridPreconditioner>(settings), 5000);
    PcgSolver pcg_bj(make_preconditioner("block_jacobi"), 5000);
    Eigen::VectorXd x, Ax;
    const LinearSolveReport r = pcg_mg.solve(H, b, x, 1e-8, bar.context());
    ASSERT_TRUE(r.converged) << n;
    H.apply(x, Ax);
    EXPECT_LE((Ax - b).norm(), 1.01e-8 * b.norm());
    EXPECT_GE(dynamic_cast<MultigridPreconditioner&>(pcg_mg.preconditioner()).levels(), 2);
    mg.push_back(r.iterations);
    bj.push_back(pcg_bj.solve(H, b, x, 1e-8, bar.context()).iterations);
    std::printf("n = %d (%d hexahedra): multigrid %d, block_jacobi %d PCG iterations to 1e-8\n", n, 2 * n * n * n,
                mg.back(), bj.back());
  }
  EXPECT_LE(mg[2], mg[1] + 5);
  EXPECT_GT(bj[2], 2 * mg[2]);
  EXPECT_GT(bj[2], bj[1]);
}

// A true Hessian that is indefinite at the coarsest level is no error: PCG ends unconverged
// (Newton then falls back to the projected Hessian), as with the direct solver. Found by
// preconditioner_bench at 16 x 16 x 32 hexahedra, where the throw stopped the Newton solve.
TEST(MultigridPreconditioner, AnIndefiniteTrueHessianEndsThePcgSolveUnconverged) {
  Bar bar(Eigen::Vector3i(4, 4, 6), 0.45);
  const LinearOperator& H = bar.problem->hessian(bar.x);
  const Eigen::SparseMatrix<double> negative = -*H.matrix();
  const SparseOperator N(negative);
  SolverContext indefinite = bar.context();
  indefinite.may_be_indefinite = true;
  PcgSolver pcg(std::make_unique<MultigridPreconditioner>(MultigridSettings{}), 500);
  const Eigen::VectorXd b = bar.rhs();
  Eigen::VectorXd x;
  LinearSolveReport r;
  EXPECT_NO_THROW(r = pcg.solve(N, b, x, 1e-8, indefinite));
  EXPECT_FALSE(r.converged);
  EXPECT_TRUE(x.allFinite());
  // A matrix that should be positive (projected) still fails loudly, and the preconditioner
  // works again on the next positive matrix.
  expect_contains(error_message([&] { pcg.solve(N, b, x, 1e-8, bar.context()); }), {"coarsest level"});
  EXPECT_TRUE(pcg.solve(H, b, x, 1e-8, bar.context()).converged);
}

// A Newton Hessian's pattern id stands for its pattern (no copy kept, no comparison): the next
// matrix with the same id reuses the symbolic products, and a matrix with a new pattern (a
// contact coupling two far vertices) gets new ones, as does an operator without an id.
TEST(MultigridPreconditioner, ReusesSymbolicProductsByPatternIdAndRedoesThemForANewPattern) {
  Bar bar(Eigen::Vector3i(6, 5, 7), 0.49);
  const LinearOperator& H = bar.problem->hessian(bar.x);
  ASSERT_NE(H.pattern_id(), 0u);
  const Eigen::SparseMatrix<double>& A = *H.matrix();
  const int n = static_cast<int>(A.rows() / 3);
  // The same matrix plus a coupling between the first and the last vertex.
  const VolumeMesh& mesh = bar.disc->mesh();
  std::vector<std::vector<int>> cliques;
  for (Eigen::Index e = 0; e < mesh.num_elements(); ++e) {
    std::vector<int> v(8);
    for (int a = 0; a < 8; ++a) v[static_cast<size_t>(a)] = mesh.elements(e, a);
    cliques.push_back(v);
  }
  cliques.push_back({0, n - 1});
  BlockHessian coupled(n, cliques);
  for (int c = 0; c < A.outerSize(); ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, c); it; ++it) coupled.matrix().coeffRef(it.row(), c) = it.value();
  const double k = 1e-3 * A.diagonal().cwiseAbs().maxCoeff();
  coupled.add_block(0, 0, k * Mat3::Identity());
  coupled.add_block(n - 1, n - 1, k * Mat3::Identity());
  coupled.add_block(0, n - 1, -k * Mat3::Identity());
  coupled.add_block(n - 1, 0, -k * Mat3::Identity());
  const BlockHessianOperator coupled_op(coupled);
  ASSERT_NE(coupled_op.pattern_id(), H.pattern_id());

  MultigridSettings settings;
  settings.coarsest_dofs = 30;
  const Eigen::VectorXd r = bar.rhs();
  auto fresh = [&](const LinearOperator& op) {
    MultigridPreconditioner F(settings);
    F.setup(op, bar.context());
    Eigen::VectorXd z;
    F.apply(r, z);
    return z;
  };
  MultigridPreconditioner M(settings);
  Eigen::VectorXd z;
  M.setup(H, bar.context());
  M.setup(H, bar.context());  // same id: reused
  M.apply(r, z);
  EXPECT_TRUE(z == fresh(H));
  M.setup(coupled_op, bar.context());  // new id: new symbolic products
  M.apply(r, z);
  EXPECT_TRUE(z == fresh(coupled_op));
  const SparseOperator plain(A);  // no id: compared with a kept copy of the pattern
  ASSERT_EQ(plain.pattern_id(), 0u);
  M.setup(plain, bar.context());
  M.apply(r, z);
  EXPECT_TRUE(z == fresh(H));
  M.setup(coupled_op, bar.context());
  M.apply(r, z);
  EXPECT_TRUE(z == fresh(coupled_op));
}

TEST(MultigridPreconditioner, IsBlockJacobiWithoutALatticeAndNeedsTheMatrix) {
  Bar bar(Eigen::Vector3i(3, 3, 3), 0.3);
  const LinearOperator& H = bar.problem->hessian(bar.x);
  const Eigen::VectorXd r = bar.rhs();
  MultigridPreconditioner M;
  auto bj = make_preconditioner("block_jacobi");
  const SolverContext bare{nullptr, bar.problem->fixed()};
  M.setup(H, bare);
  bj->setup(H, bare);
  Eigen::VectorXd z1, z2;
  M.apply(r, z1);
  bj->apply(r, z2);
  EXPECT_EQ(M.levels(), 1);
  EXPECT_LE((z1 - z2).norm(), 1e-15 * z2.norm());
  // With a lattice it needs the assembled matrix.
  expect_contains(error_message([&] { M.setup(test::WithoutMatrix(H), bar.context()); }), {"multigrid", "assembled matrix"});
}

}  // namespace
}  // namespace sinew
