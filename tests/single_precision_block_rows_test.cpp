// The multigrid smoother's single-precision block-row copy of the Newton matrix.
#include <gtest/gtest.h>

#include "elastic_bar_support.hpp"
#include "sinew/linalg/single_precision_block_rows.hpp"

namespace sinew {
namespace {

TEST(SinglePrecisionBlockRows, AppliesTheNewtonMatrixToSinglePrecision) {
  for (const bool tets : {false, true}) {
    test::ElasticBar bar(Eigen::Vector3i(4, 3, 5), 0.45, tets, 0.5);
    Eigen::VectorXd x = bar.x;
    for (Eigen::Index i = 0; i < x.size(); ++i) x(i) += 0.05 * std::sin(1.7 * static_cast<double>(i));
    const LinearOperator& H = bar.problem->hessian(x);
    ASSERT_NE(H.matrix(), nullptr);
    SinglePrecisionBlockRows single;
    ASSERT_TRUE(single.set(*H.matrix(), H));
    EXPECT_EQ(single.rows(), H.rows());
    const Eigen::VectorXd v = bar.rhs();
    Eigen::VectorXd exact, approximate;
    H.apply(v, exact);
    single.apply(v, approximate);
    EXPECT_LT((exact - approximate).norm(), 1e-6 * exact.norm()) << (tets ? "tets" : "hexes");
    EXPECT_GT((exact - approximate).norm(), 0.0);  // it is single precision
    EXPECT_EQ(single.diagonal_block(7), H.diagonal_block(7));
    EXPECT_GT(single.bytes(), 0u);
  }
}

TEST(SinglePrecisionBlockRows, RefusesAPatternThatIsNotMadeOfBlocks) {
  Eigen::SparseMatrix<double> A(6, 6);
  std::vector<Eigen::Triplet<double>> entries;
  for (int i = 0; i < 6; ++i) entries.emplace_back(i, i, 2.0);
  entries.emplace_back(0, 4, 1.0);  // one entry of block (0, 1), not the whole block
  entries.emplace_back(4, 0, 1.0);
  A.setFromTriplets(entries.begin(), entries.end());
  A.makeCompressed();
  SparseOperator op(A);
  SinglePrecisionBlockRows single;
  EXPECT_FALSE(single.set(A, op));
  // The full blocks are accepted.
  Eigen::SparseMatrix<double> B(6, 6);
  std::vector<Eigen::Triplet<double>> full;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) full.emplace_back(i, j, i == j ? 10.0 : 1.0 / (1 + i + j));
  B.setFromTriplets(full.begin(), full.end());
  B.makeCompressed();
  SparseOperator full_op(B);
  ASSERT_TRUE(single.set(B, full_op));
  const Eigen::VectorXd v = Eigen::VectorXd::LinSpaced(6, -1.0, 2.0);
  Eigen::VectorXd y;
  single.apply(v, y);
  EXPECT_LT((y - B * v).norm(), 1e-6 * (B * v).norm());
}

}  // namespace
}  // namespace sinew
