#pragma once
// A random SPD matrix with 3x3 vertex blocks coupling each vertex to a few others, built as
// B^T B + 0.1 I: the shape (not the values) of an assembled FEM Hessian, for solver tests.
#include <Eigen/Sparse>
#include <random>
#include <vector>

namespace sinew::test {

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

}  // namespace sinew::test
