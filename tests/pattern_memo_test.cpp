// PatternMemo: a pattern id answers without a kept copy, a matrix without one is compared, and
// the two CHOLMOD users (the direct solver, the lagged Cholesky preconditioner) analyse a new
// pattern that arrives under a new id.
#include <gtest/gtest.h>

#include "spd_test_support.hpp"

#include "sinew/linalg/linear_operator.hpp"
#include "sinew/linalg/pattern_memo.hpp"
#include "sinew/solver/linear_solver.hpp"
#include "sinew/solver/preconditioner.hpp"

namespace sinew {
namespace {

using test::random_spd;

// A SparseOperator that reports a given pattern id.
class IdentifiedOperator final : public LinearOperator {
 public:
  IdentifiedOperator(const Eigen::SparseMatrix<double>& A, std::uint64_t id) : op_(A), A_(&A), id_(id) {}
  Eigen::Index rows() const override { return op_.rows(); }
  void apply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const override { op_.apply(x, y); }
  Mat3 diagonal_block(Eigen::Index v) const override { return op_.diagonal_block(v); }
  const Eigen::SparseMatrix<double>* matrix() const override { return A_; }
  std::uint64_t pattern_id() const override { return id_; }

 private:
  SparseOperator op_;
  const Eigen::SparseMatrix<double>* A_;
  std::uint64_t id_;
};

// A with one more coupling block (vertices 0 and n - 1): another pattern of the same size.
Eigen::SparseMatrix<double> with_extra_block(const Eigen::SparseMatrix<double>& A) {
  Eigen::SparseMatrix<double> B = A;
  const Eigen::Index n = A.rows();
  for (int i = 0; i < 3; ++i) {
    B.coeffRef(i, n - 3 + i) += 0.01;
    B.coeffRef(n - 3 + i, i) += 0.01;
  }
  B.makeCompressed();
  return B;
}

TEST(PatternMemo, IdsAnswerWithoutACopyAndMatricesWithoutOneAreCompared) {
  const Eigen::SparseMatrix<double> A = random_spd(40, 3);
  const Eigen::SparseMatrix<double> B = with_extra_block(A);
  ASSERT_NE(A.nonZeros(), B.nonZeros());
  PatternMemo memo;
  EXPECT_FALSE(memo.same_or_remember(A, 7));
  EXPECT_TRUE(memo.same_or_remember(A, 7));
  EXPECT_TRUE(memo.same_or_remember(B, 7));  // the id stands for the pattern: not compared
  EXPECT_EQ(memo.bytes(), 0u);
  EXPECT_FALSE(memo.same_or_remember(A, 8));
  EXPECT_FALSE(memo.same_or_remember(A, 0));  // no id: compared from now on
  EXPECT_GT(memo.bytes(), 0u);
  Eigen::SparseMatrix<double> scaled = 2.0 * A;  // other values, same pattern
  scaled.makeCompressed();
  EXPECT_TRUE(memo.same_or_remember(scaled, 0));
  EXPECT_FALSE(memo.same_or_remember(B, 0));
  EXPECT_TRUE(memo.same_or_remember(B, 0));
  Eigen::SparseMatrix<double> gaps = B;
  gaps.uncompress();
  EXPECT_FALSE(memo.same_or_remember(gaps, 0));  // arrays with gaps: never taken as the same
  EXPECT_FALSE(memo.same_or_remember(B, 0));
  EXPECT_FALSE(memo.same_or_remember(B, 9));  // an id after none: analysed again
  EXPECT_EQ(memo.bytes(), 0u);
}

TEST(PatternMemo, CholmodUsersAnalyseANewPatternUnderANewId) {
  const Eigen::SparseMatrix<double> A = random_spd(300, 5);
  const Eigen::SparseMatrix<double> B = with_extra_block(A);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(A.rows(), -1.0, 1.0);
  LinearSolverSettings s;
  s.kind = "cholmod";
  auto direct = make_linear_solver(s);
  s.kind = "pcg";
  s.preconditioner = "lagged_cholesky";
  auto lagged = make_linear_solver(s);
  // A, then B under a new id, then A again under a third: each solve answers its own matrix.
  std::uint64_t id = 11;
  for (const Eigen::SparseMatrix<double>* M : {&A, &B, &A}) {
    const IdentifiedOperator op(*M, id++);
    for (LinearSolver* solver : {direct.get(), lagged.get()}) {
      Eigen::VectorXd x;
      ASSERT_TRUE(solver->solve(op, b, x, 1e-12).converged) << solver->name();
      EXPECT_LT((*M * x - b).norm(), 1e-10 * b.norm()) << solver->name() << ", id " << id - 1;
    }
  }
}

}  // namespace
}  // namespace sinew
