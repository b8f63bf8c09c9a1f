// BlockCholesky: the 3x3-block sparse Cholesky factorisation against Eigen's dense and simplicial
// ones, its forward-only Gram matrix, a changed pattern and an indefinite matrix.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <cmath>

#include "sinew/solver/block_cholesky.hpp"

namespace sinew {
namespace {

// A lattice of nx x ny x nz cells (27-point vertex stencil) with full, non-symmetric-looking
// 3x3 coupling blocks, made symmetric and diagonally dominant: the structure of M + h^2 K on
// hexahedra.
Eigen::SparseMatrix<double> block_lattice(int nx, int ny, int nz, double diagonal) {
  const int sy = ny + 1, sz = nz + 1;
  auto id = [&](int i, int j, int k) { return (i * sy + j) * sz + k; };
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i <= nx; ++i)
    for (int j = 0; j <= ny; ++j)
      for (int k = 0; k <= nz; ++k)
        for (int di = -1; di <= 1; ++di)
          for (int dj = -1; dj <= 1; ++dj)
            for (int dk = -1; dk <= 1; ++dk) {
              const int a = i + di, b = j + dj, c = k + dk;
              if (a < 0 || b < 0 || c < 0 || a > nx || b > ny || c > nz) continue;
              const int u = id(i, j, k), v = id(a, b, c);
              for (int p = 0; p < 3; ++p)
                for (int q = 0; q < 3; ++q)
                  t.emplace_back(3 * u + p, 3 * v + q,
                                 u == v ? (p == q ? diagonal : 0.5 * std::sin(p + q + u))
                                        : -(p == q ? 1.0 : 0.2 * std::cos(p + 2 * q + u + v)));
            }
  const int n = 3 * (nx + 1) * sy * sz;
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  Eigen::SparseMatrix<double> S = 0.5 * (A + Eigen::SparseMatrix<double>(A.transpose()));
  S.makeCompressed();
  return S;
}

TEST(BlockCholesky, SolvesLikeADenseFactorisation) {
  for (const auto& [nx, ny, nz] : {std::array<int, 3>{14, 2, 2}, std::array<int, 3>{3, 3, 3}}) {
    const Eigen::SparseMatrix<double> A = block_lattice(nx, ny, nz, 30.0);
    ASSERT_TRUE(BlockCholesky::suits(A));
    BlockCholesky F;
    F.analyze(A);
    ASSERT_TRUE(F.factorize(A));
    const Eigen::Index n = A.rows();
    const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, -1.0, 2.0);
    const Eigen::VectorXd expected = Eigen::MatrixXd(A).llt().solve(b);
    EXPECT_LT((F.solve(b) - expected).norm(), 1e-13 * expected.norm());
    const Eigen::MatrixXd B = Eigen::MatrixXd::Identity(n, 4);
    const Eigen::MatrixXd X = F.solve(B);
    EXPECT_LT((Eigen::MatrixXd(A) * X - B).norm(), 1e-13);
    // The same cost counts as the scalar factor of a fill-reducing ordering, within a factor.
    Eigen::SimplicialLLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::AMDOrdering<int>> scalar(A);
    const double scalar_lnz = static_cast<double>(scalar.matrixL().nestedExpression().nonZeros());
    EXPECT_GT(F.nonzeros(), 0.5 * scalar_lnz);
    EXPECT_LT(F.nonzeros(), 2.0 * scalar_lnz);
    EXPECT_GT(F.flops(), F.nonzeros());
  }
}

TEST(BlockCholesky, GramMatrixOfSparseRowsMatchesFullSolves) {
  const Eigen::SparseMatrix<double> A = block_lattice(14, 2, 2, 30.0);
  const Eigen::Index n = A.rows();
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < 7; ++i)  // sparse rows of 24 entries, like an element's constraint row
    for (int k = 0; k < 24; ++k) t.emplace_back(i, (53 * i + 17 * k) % n, std::sin(1.0 + i + 0.3 * k));
  Eigen::SparseMatrix<double, Eigen::RowMajor> J(7, n);
  J.setFromTriplets(t.begin(), t.end());
  BlockCholesky F;
  F.analyze(A);
  ASSERT_TRUE(F.factorize(A));
  const Eigen::MatrixXd expected = J * F.solve(Eigen::MatrixXd(J.transpose()));
  const Eigen::MatrixXd W = F.gram(J);
  EXPECT_LT((W - expected).norm(), 1e-13 * expected.norm());
  EXPECT_LT((W - W.transpose()).norm(), 1e-15 * W.norm());
}

TEST(BlockCholesky, SolvesManyRightHandSidesAsOneAtATime) {
  // Columns like the LCP's J^T (sparse, zero above their first vertex in any order) and dense
  // ones, a count that is not a whole number of vectors: each column as its own solve gives.
  const Eigen::SparseMatrix<double> A = block_lattice(6, 3, 2, 30.0);
  const Eigen::Index n = A.rows();
  BlockCholesky F;
  F.analyze(A);
  ASSERT_TRUE(F.factorize(A));
  for (const int m : {1, 11}) {
    Eigen::MatrixXd B = Eigen::MatrixXd::Zero(n, m);
    for (int c = 0; c < m; ++c) {
      if (c % 3 == 2) {
        B.col(c) = Eigen::VectorXd::LinSpaced(n, -1.0 - c, 2.0 + c);
        continue;
      }
      for (int k = 0; k < 24; ++k) B((41 * c + 13 * k) % n, c) = std::sin(1.0 + c + 0.7 * k);
    }
    const Eigen::MatrixXd X = F.solve(B);
    ASSERT_EQ(X.rows(), n);
    ASSERT_EQ(X.cols(), m);
    for (int c = 0; c < m; ++c) {
      const Eigen::VectorXd x = F.solve(Eigen::VectorXd(B.col(c)));
      EXPECT_LT((X.col(c) - x).norm(), 1e-14 * x.norm()) << "column " << c << " of " << m;
    }
    EXPECT_LT((Eigen::MatrixXd(A) * X - B).norm(), 1e-12 * B.norm());
  }
}

TEST(BlockCholesky, ReadsTheLowerTriangleAndFollowsNewValuesAndPatterns) {
  const Eigen::SparseMatrix<double> A = block_lattice(4, 2, 2, 30.0);
  BlockCholesky F;
  F.analyze(A);
  // Only the lower triangle counts (as for Eigen's Lower factorisations).
  Eigen::SparseMatrix<double> upper_changed = A;
  for (Eigen::Index c = 0; c < upper_changed.outerSize(); ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(upper_changed, c); it; ++it)
      if (it.row() < it.col()) it.valueRef() += 100.0;
  ASSERT_TRUE(F.factorize(upper_changed));
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(A.rows(), -1.0, 2.0);
  const Eigen::VectorXd x = F.solve(b);
  EXPECT_LT((A * x - b).norm(), 1e-13 * b.norm());
  // New values with the same pattern, then a smaller pattern (analysed again on its own).
  const Eigen::SparseMatrix<double> A2 = block_lattice(4, 2, 2, 40.0);
  ASSERT_TRUE(F.factorize(A2));
  EXPECT_LT((A2 * F.solve(b) - b).norm(), 1e-13 * b.norm());
  const Eigen::SparseMatrix<double> A3 = block_lattice(3, 2, 2, 30.0);
  ASSERT_TRUE(F.factorize(A3));
  const Eigen::VectorXd b3 = Eigen::VectorXd::LinSpaced(A3.rows(), -1.0, 2.0);
  EXPECT_LT((A3 * F.solve(b3) - b3).norm(), 1e-13 * b3.norm());
}

TEST(BlockCholesky, RejectsIndefiniteMatricesAndScalarPatterns) {
  const Eigen::SparseMatrix<double> A = block_lattice(3, 2, 2, -30.0);
  BlockCholesky F;
  F.analyze(A);
  EXPECT_FALSE(F.factorize(A));
  // A DOF-wise (diagonal-block) coupling fills a third of each vertex block: the scalar
  // factorisations suit it better.
  Eigen::SparseMatrix<double> diagonal_blocks(30, 30);
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < 30; ++i) {
    t.emplace_back(i, i, 4.0);
    if (i + 3 < 30) {
      t.emplace_back(i, i + 3, -1.0);
      t.emplace_back(i + 3, i, -1.0);
    }
  }
  diagonal_blocks.setFromTriplets(t.begin(), t.end());
  EXPECT_FALSE(BlockCholesky::suits(diagonal_blocks));
  EXPECT_FALSE(BlockCholesky::suits(Eigen::SparseMatrix<double>(31, 31)));
}

}  // namespace
}  // namespace sinew
