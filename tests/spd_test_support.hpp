#pragma once
// A random SPD matrix with 3x3 vertex blocks coupling each vertex to a few others, built as
// B^T B + 0.1 I: the shape (not the values) of an assembled FEM Hessian, for solver tests.
#include <gtest/gtest.h>

#include <Eigen/Sparse>
#include <cmath>
#include <random>
#include <vector>

#include "sinew/linalg/linear_operator.hpp"

namespace sinew::test {

// An operator seen without its matrix (matrix() is null): what a matrix-free Hessian looks like
// to a preconditioner that needs the assembled one.
class WithoutMatrix final : public LinearOperator {
 public:
  explicit WithoutMatrix(const LinearOperator& A) : A_(A) {}
  Eigen::Index rows() const override { return A_.rows(); }
  void apply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const override { A_.apply(x, y); }
  Mat3 diagonal_block(Eigen::Index v) const override { return A_.diagonal_block(v); }

 private:
  const LinearOperator& A_;
};

inline Eigen::SparseMatrix<double> random_spd(int vertices, unsigned seed) {
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
  return Eigen::SparseMatrix<double>(B.transpose()) * B + 0.1 * I;
}

// A preconditioner M (anything with apply(r, z)) acts as a symmetric positive definite operator
// on the free DOFs and leaves the fixed ones (mask `fixed`) at zero, up to `fixed_tolerance`
// relative to |M u|: checked with u (the right-hand side given) and a second vector. Symmetric
// to `symmetry_tolerance` (relative): round-off of double products by default; a preconditioner
// that applies a single-precision operator is symmetric only to that precision.
template <class Preconditioner>
void expect_symmetric_positive(Preconditioner& M, const Eigen::VectorXd& u, const std::vector<char>& fixed,
                               double fixed_tolerance = 0.0, double symmetry_tolerance = 1e-10) {
  Eigen::VectorXd v(u.size()), Mu, Mv;
  for (Eigen::Index i = 0; i < v.size(); ++i) v(i) = fixed[static_cast<size_t>(i)] ? 0.0 : std::sin(1.3 * static_cast<double>(i));
  M.apply(u, Mu);
  M.apply(v, Mv);
  EXPECT_NEAR(u.dot(Mv), v.dot(Mu), symmetry_tolerance * u.norm() * Mv.norm());
  EXPECT_GT(u.dot(Mu), 0.0);
  EXPECT_GT(v.dot(Mv), 0.0);
  for (Eigen::Index i = 0; i < u.size(); ++i)
    if (fixed[static_cast<size_t>(i)]) {
      EXPECT_LE(std::abs(Mu(i)), fixed_tolerance * Mu.norm()) << "fixed DOF " << i;  // no correction moves a fixed DOF
    }
}

}  // namespace sinew::test
