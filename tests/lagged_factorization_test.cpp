// LaggedFactorization: exact solves with a matrix from an older factorisation (preconditioned
// CG), the rent-or-buy refresh and the fallback when CG needs too long.
#include <gtest/gtest.h>

#include <algorithm>

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

// A 3D lattice Laplacian plus mass with 3 DOFs per vertex (cells along x, 2 x 2 across): the
// fill of paper 001's beam.
Eigen::SparseMatrix<double> lattice_matrix(int cells, double mass) {
  const int sx = cells + 1, side = 3;
  auto dof = [&](int i, int j, int k, int d) { return 3 * ((i * side + j) * side + k) + d; };
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < sx; ++i)
    for (int j = 0; j < side; ++j)
      for (int k = 0; k < side; ++k)
        for (int d = 0; d < 3; ++d) {
          t.emplace_back(dof(i, j, k, d), dof(i, j, k, d), mass);
          for (int di = -1; di <= 1; ++di)
            for (int dj = -1; dj <= 1; ++dj)
              for (int dk = -1; dk <= 1; ++dk) {
                const int a = i + di, b = j + dj, c = k + dk;
                if ((di == 0 && dj == 0 && dk == 0) || a < 0 || b < 0 || c < 0 || a >= sx || b >= side || c >= side)
                  continue;
                t.emplace_back(dof(i, j, k, d), dof(i, j, k, d), 1.0);
                t.emplace_back(dof(i, j, k, d), dof(a, b, c, d), -1.0);
              }
        }
  const Eigen::Index n = 3 * sx * side * side;
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

TEST(LaggedFactorization, SmallMatricesGetEigensSimplicialFactorWithCholmodsAnswers) {
  // Below `block_factorization_below` rows (and with short columns of L) the factorisation is
  // Eigen's simplicial LLT instead of CHOLMOD's supernodal one: the same solves, lagged solves and
  // cost estimate up to rounding.
  const Eigen::SparseMatrix<double> A1 = lattice_matrix(14, 1.0), A2 = lattice_matrix(14, 1.2);  // 405 DOFs
  const Eigen::Index n = A1.rows();
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, -1.0, 2.0);
  const Eigen::MatrixXd B = Eigen::MatrixXd::Identity(n, 5);
  FactorizationReuse simplicial, cholmod;
  simplicial.cg_tolerance = cholmod.cg_tolerance = 1e-12;
  simplicial.max_cg_iterations = cholmod.max_cg_iterations = 100;
  cholmod.block_factorization_below = 0;
  ASSERT_GT(simplicial.block_factorization_below, n);
  LaggedFactorization S, C;
  LaggedFactorization::Counters cs, cc;
  S.use(A1, simplicial, cs);
  C.use(A1, cholmod, cc);
  Eigen::VectorXd xs, xc;
  S.solve(b, xs, false, cs);
  C.solve(b, xc, false, cc);
  EXPECT_LT((A1 * xs - b).norm(), 1e-12 * b.norm());
  EXPECT_LT((xs - xc).norm(), 1e-12 * xc.norm());
  EXPECT_LT((S.apply_inverse(B) - C.apply_inverse(B)).norm(), 1e-12 * C.apply_inverse(B).norm());
  // Both estimate the cost of a refresh from the factor's own counts (different orderings).
  EXPECT_GT(S.refresh_cost(), 0.0);
  EXPECT_GT(C.refresh_cost(), 0.0);
  EXPECT_LT(S.refresh_cost(), 3.0 * C.refresh_cost());
  EXPECT_GT(S.refresh_cost(), C.refresh_cost() / 3.0);

  // The lagged factorisation of A1 solves with A2 by CG either way.
  S.use(A2, simplicial, cs);
  C.use(A2, cholmod, cc);
  S.solve(b, xs, false, cs);
  C.solve(b, xc, false, cc);
  EXPECT_EQ(cs.factorizations, 1);
  EXPECT_EQ(cc.factorizations, 1);
  EXPECT_GT(cs.cg_iterations, 1);
  EXPECT_LT((A2 * xs - b).norm(), 1e-11 * b.norm());
  EXPECT_LT((xs - xc).norm(), 1e-10 * xc.norm());
}

// T (x) B for the 1D Laplacian plus mass T over `vertices` vertices and B = I + 0.1 ones: full 3x3
// vertex blocks, SPD; plus `coupling` between DOFs 0 and 7 where it is not 0 (a pattern whose
// vertex columns no longer share their rows).
Eigen::SparseMatrix<double> block_matrix(int vertices, double mass, double coupling) {
  std::vector<Eigen::Triplet<double>> t;
  for (int a = 0; a < vertices; ++a)
    for (int b = std::max(a - 1, 0); b <= std::min(a + 1, vertices - 1); ++b) {
      const double tab = a == b ? mass + 2.0 : -1.0;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) t.emplace_back(3 * a + i, 3 * b + j, tab * ((i == j ? 1.0 : 0.0) + 0.1));
    }
  if (coupling != 0.0) {
    t.emplace_back(0, 7, coupling);
    t.emplace_back(7, 0, coupling);
  }
  Eigen::SparseMatrix<double> A(3 * vertices, 3 * vertices);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

TEST(LaggedFactorization, PatternIdsSkipOnlyTheComparisonsOfPatternsAlreadySeen) {
  // Under the id of a pattern already seen, CG's product and the block factorisation take the
  // matrix's pattern as known; a new id makes them look at the new pattern: the lagged solves
  // with it, then its own factorisation, are still exact.
  const Eigen::SparseMatrix<double> A1 = block_matrix(30, 1.0, 0.0), A2 = block_matrix(30, 1.2, 0.05);
  ASSERT_NE(A1.nonZeros(), A2.nonZeros());
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(A1.rows(), -1.0, 2.0);
  FactorizationReuse reuse;
  reuse.cg_tolerance = 1e-12;
  reuse.max_cg_iterations = 100;
  LaggedFactorization F;
  LaggedFactorization::Counters c;
  Eigen::VectorXd x;
  F.use(A1, reuse, c, 1);
  F.solve(b, x, false, c);
  EXPECT_LT((A1 * x - b).norm(), 1e-12 * b.norm());
  F.use(A1, reuse, c, 1);  // lagged now: CG's product takes A1's pattern (no iteration from x)
  F.solve(b, x, true, c);
  EXPECT_EQ(c.cg_iterations, 0);
  F.use(A2, reuse, c, 2);
  EXPECT_FALSE(F.exact());  // lagged: CG with A2's products
  F.solve(b, x, false, c);
  EXPECT_LT((A2 * x - b).norm(), 1e-11 * b.norm());
  const Eigen::VectorXd b2 = Eigen::VectorXd::LinSpaced(A1.rows(), 3.0, -1.0);
  F.solve(b2, x, false, c);  // the same id: the pattern taken as known
  EXPECT_LT((A2 * x - b2).norm(), 1e-11 * b2.norm());
  F.refactor(c);  // A2's own factorisation
  EXPECT_TRUE(F.exact());
  F.solve(b, x, false, c);
  EXPECT_LT((A2 * x - b).norm(), 1e-12 * b.norm());
  EXPECT_EQ(c.factorizations, 2);
}

TEST(LaggedFactorization, GramMatrixMatchesTheColumnsOfEitherFactor) {
  // gram(J) = J P^-1 J^T: by forward substitutions alone for the simplicial factor, by full
  // solves for CHOLMOD's; both against J times the columns P^-1 J^T.
  const Eigen::SparseMatrix<double> A = lattice_matrix(14, 1.0);  // 405 DOFs
  const Eigen::Index n = A.rows();
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < 7; ++i)  // sparse rows of 24 entries, like an element's constraint row
    for (int k = 0; k < 24; ++k) t.emplace_back(i, (53 * i + 17 * k) % n, std::sin(1.0 + i + 0.3 * k));
  Eigen::SparseMatrix<double, Eigen::RowMajor> J(7, n);
  J.setFromTriplets(t.begin(), t.end());
  const Eigen::MatrixXd Jt = Eigen::MatrixXd(J.transpose());
  for (const int block_factorization_below : {1000, 0}) {
    FactorizationReuse reuse;
    reuse.block_factorization_below = block_factorization_below;
    LaggedFactorization F;
    LaggedFactorization::Counters counters;
    F.use(A, reuse, counters);
    const Eigen::MatrixXd expected = J * F.apply_inverse(Jt);
    const Eigen::MatrixXd W = F.gram(J);
    ASSERT_EQ(W.rows(), 7);
    ASSERT_EQ(W.cols(), 7);
    EXPECT_LT((W - expected).norm(), 1e-12 * expected.norm()) << "block_factorization_below " << block_factorization_below;
    EXPECT_LT((W - W.transpose()).norm(), 1e-14 * W.norm());
  }
}

}  // namespace
}  // namespace sinew
