// LaggedFactorization: exact solves with a matrix from an older factorisation (preconditioned
// CG), the rent-or-buy refresh and the fallback when CG needs too long.
#include <gtest/gtest.h>

#include "sinew/solver/lagged_factorization.hpp"

namespace sinew {
namespace {

// A 1D Laplacian plus mass: SPD, tridiagonal, the shape of M + h^2 K.
Eigen::SparseMatrix<double> matrix(Eigen::Index n, double mass, double stiffness) {
  std::vector<Eigen::Triplet<double>> t;
  for (Eigen::Index i = 0; i < n; ++i) {
    t.emplace_back(i, i, mass + 2.0 * stiffness);
    if (i + 1 < n) {
      t.emplace_back(i, i + 1, -stiffness);
      t.emplace_back(i + 1, i, -stiffness);
    }
  }
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

TEST(LaggedFactorization, SolvesANewMatrixWithAnOldFactorisationToTheCgTolerance) {
  const Eigen::Index n = 200;
  const Eigen::SparseMatrix<double> A1 = matrix(n, 1.0, 1.0), A2 = matrix(n, 1.0, 1.3);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, -1.0, 2.0);
  FactorizationReuse reuse;
  reuse.cg_tolerance = 1e-10;
  reuse.max_cg_iterations = 50;
  LaggedFactorization F;
  LaggedFactorization::Counters c;
  F.use(A1, reuse, c);  // first use: factorises
  EXPECT_EQ(c.factorizations, 1);
  EXPECT_TRUE(F.exact());
  Eigen::VectorXd x;
  F.solve(b, x, false, c);
  EXPECT_LT((A1 * x - b).norm(), 1e-12 * b.norm());
  EXPECT_EQ(c.cg_iterations, 0);  // direct

  F.use(A2, reuse, c);  // budget not spent: keeps the factorisation of A1
  EXPECT_EQ(c.factorizations, 1);
  EXPECT_FALSE(F.exact());
  F.solve(b, x, false, c);
  EXPECT_LT((A2 * x - b).norm(), 1e-10 * b.norm());
  EXPECT_GT(c.cg_iterations, 1);
  const int first = c.cg_iterations;
  F.solve(b, x, true, c);  // from the solution itself: nothing left to do
  EXPECT_EQ(c.cg_iterations, first);

  // Columns belong to one factorisation: a refresh drops them.
  F.columns()[7] = {{{0, 1.0}}, Eigen::VectorXd::Ones(n)};
  F.refactor(c);
  EXPECT_EQ(c.factorizations, 2);
  EXPECT_TRUE(F.columns().empty());
  EXPECT_GT(F.refresh_cost(), 0.0);
}

TEST(LaggedFactorization, RefreshesWhenTheCgWorkReachesAFactorisationOrOneSolveTakesTooLong) {
  const Eigen::Index n = 300;
  const Eigen::SparseMatrix<double> A1 = matrix(n, 1.0, 1.0), A2 = matrix(n, 1.0, 50.0);
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(n);
  FactorizationReuse reuse;
  LaggedFactorization F;
  LaggedFactorization::Counters c;
  F.use(A1, reuse, c);
  // Very different matrix: CG with the old factorisation cannot finish within 2 iterations.
  reuse.max_cg_iterations = 2;
  reuse.cg_tolerance = 1e-12;
  F.use(A2, reuse, c);
  EXPECT_EQ(c.factorizations, 1);
  Eigen::VectorXd x;
  F.solve(b, x, false, c);
  EXPECT_EQ(c.factorizations, 2);  // fell back to factorising A2
  EXPECT_TRUE(F.exact());
  EXPECT_LT((A2 * x - b).norm(), 1e-12 * b.norm());

  // Rent or buy: keep solving with a lagged factorisation until the CG iterations spent reach
  // refresh_cost(); the next use() then refactorises.
  reuse.max_cg_iterations = 1000;
  reuse.cg_tolerance = 1e-10;
  F.use(A1, reuse, c);
  const int factorizations = c.factorizations;
  int spent = 0;
  while (spent < F.refresh_cost()) {
    const int before = c.cg_iterations;
    F.solve(b, x, false, c);
    spent += c.cg_iterations - before;
    ASSERT_GT(c.cg_iterations, before);
    ASSERT_EQ(c.factorizations, factorizations);
  }
  F.use(A1, reuse, c);
  EXPECT_EQ(c.factorizations, factorizations + 1);

  reuse.enabled = false;  // no reuse: every use() factorises
  F.use(A2, reuse, c);
  F.use(A2, reuse, c);
  EXPECT_EQ(c.factorizations, factorizations + 3);
}

}  // namespace
}  // namespace sinew
