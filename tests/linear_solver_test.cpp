// The linear-solver layer: the parallel sparse product, its diagonal blocks, and PCG (both
// preconditioners) against CHOLMOD on a symmetric positive definite block system.
#include <gtest/gtest.h>

#include <random>

#include "sinew/linalg/linear_operator.hpp"
#include "sinew/solver/linear_solver.hpp"

namespace sinew {
namespace {

// A random SPD matrix with 3x3 vertex blocks coupling each vertex to a few others, built as
// B^T B + shift I, the shape (not the values) of an assembled FEM Hessian.
Eigen::SparseMatrix<double> random_spd(int vertices, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::uniform_int_distribution<int> pick(0, vertices - 1);
  std::vector<Eigen::Triplet<double>> t;
  const int n = 3 * vertices;
  for (int r = 0; r < n; ++r)
    for (int k = 0; k < 4; ++k) t.emplace_back(r, 3 * pick(rng) + k % 3, u(rng));
  Eigen::SparseMatrix<double> B(n, n);
  B.setFromTriplets(t.begin(), t.end());
  Eigen::SparseMatrix<double> I(n, n);
  I.setIdentity();
  Eigen::SparseMatrix<double> A = Eigen::SparseMatrix<double>(B.transpose()) * B + 0.1 * I;
  return A;
}

TEST(LinearSolver, ParallelProductMatchesEigen) {
  for (unsigned seed : {1u, 2u, 3u}) {
    Eigen::SparseMatrix<double> A = random_spd(2000, seed);
    const Eigen::VectorXd x = Eigen::VectorXd::Random(A.rows());
    const SparseOperator op(A);
    Eigen::VectorXd y;
    op.apply(x, y);
    EXPECT_LE((y - A * x).norm(), 1e-12 * (A * x).norm());
    // An uncompressed matrix (the state after inserting into a fixed pattern) too.
    A.uncompress();
    op.apply(x, y);
    EXPECT_LE((y - A * x).norm(), 1e-12 * (A * x).norm());
    for (Eigen::Index v : {Eigen::Index{0}, Eigen::Index{777}, Eigen::Index{1999}})
      EXPECT_EQ(op.diagonal_block(v), Mat3(Eigen::MatrixXd(A).block(3 * v, 3 * v, 3, 3)));
  }
}

TEST(LinearSolver, PcgMatchesCholmodWithEitherPreconditioner) {
  const Eigen::SparseMatrix<double> A = random_spd(500, 7);
  const SparseOperator op(A);
  const Eigen::VectorXd b = Eigen::VectorXd::Random(A.rows());
  Eigen::VectorXd direct;
  LinearSolverSettings s;
  s.kind = "cholmod";
  ASSERT_TRUE(make_linear_solver(s)->solve(op, b, direct, 0.0).converged);
  for (Preconditioner p : {Preconditioner::Jacobi, Preconditioner::BlockJacobi3}) {
    s.kind = "pcg";
    s.preconditioner = p;
    auto pcg = make_linear_solver(s);
    Eigen::VectorXd x;
    const LinearSolveReport r = pcg->solve(op, b, x, 1e-10);
    EXPECT_TRUE(r.converged) << pcg->name();
    EXPECT_GT(r.iterations, 1);
    EXPECT_LE((A * x - b).norm(), 1.01e-10 * b.norm()) << pcg->name();
    EXPECT_LE(r.relative_residual, 1e-10);
    EXPECT_LE((x - direct).norm(), 1e-6 * direct.norm()) << pcg->name();
  }
}

TEST(LinearSolver, PcgReportsAnUnconvergedSolve) {
  const Eigen::SparseMatrix<double> A = random_spd(500, 8);
  LinearSolverSettings s;
  s.kind = "pcg";
  s.max_iterations = 3;
  Eigen::VectorXd x;
  const LinearSolveReport r = make_linear_solver(s)->solve(SparseOperator(A), Eigen::VectorXd::Ones(A.rows()), x, 1e-12);
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(r.iterations, 3);
  EXPECT_GT(r.relative_residual, 1e-12);
}

TEST(LinearSolver, PcgReturnsZeroForAZeroRightHandSide) {
  const Eigen::SparseMatrix<double> A = random_spd(50, 9);
  LinearSolverSettings s;
  s.kind = "pcg";
  Eigen::VectorXd x = Eigen::VectorXd::Ones(A.rows());
  const LinearSolveReport r = make_linear_solver(s)->solve(SparseOperator(A), Eigen::VectorXd::Zero(A.rows()), x, 1e-8);
  EXPECT_TRUE(r.converged);
  EXPECT_EQ(x.norm(), 0.0);
}

}  // namespace
}  // namespace sinew
