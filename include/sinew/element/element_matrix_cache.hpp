#pragma once
// Per-element symmetric stiffness matrices kept for a matrix-free Hessian product: the 3x3
// blocks K_ab (a <= b) of each element in single precision (a hexahedron: 36 blocks, 1,296
// bytes, against ~4 kB per hexahedron for the assembled double matrix with its indices).
// y += sum_e K_e x_e runs over the mesh's colour groups, so no two tasks write one vertex.
#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "sinew/core/types.hpp"
#include "sinew/element/discretization.hpp"

namespace sinew {

class ElementMatrixCache {
 public:
  // Storage for every element of `d` (kept by reference: it must outlive the cache).
  void resize(const Discretization& d);
  bool empty() const { return values_.empty(); }

  // Stores block K_ab (a <= b, node indices within element e) in single precision.
  void store(Eigen::Index e, int a, int b, const Mat3& K);

  // y += K x over all elements (x and y in the mesh's global DOF numbering).
  void add_product(const Eigen::VectorXd& x, Eigen::VectorXd& y) const;
  // Element e's whole symmetric matrix (3 nodes x 3 nodes, node order of the element) into the
  // top-left corner of K, in double.
  void unpack(Eigen::Index e, Eigen::Ref<Eigen::MatrixXd> K) const;
  // diagonal[v] += sum over elements of the vertex's diagonal blocks.
  void add_diagonal(std::vector<Mat3>& diagonal) const;
  std::size_t bytes() const { return values_.size() * sizeof(float); }

 private:
  std::size_t block_index(int a, int b) const { return static_cast<std::size_t>(pair_[static_cast<std::size_t>(a * nodes_ + b)]); }
  const Discretization* d_ = nullptr;
  int nodes_ = 0;
  int blocks_ = 0;          // upper blocks per element: nodes (nodes + 1) / 2
  std::vector<int> pair_;   // (a, b) with a <= b -> block number
  std::vector<float> values_;  // per element, per block, 9 entries column-major
};

}  // namespace sinew
