#pragma once
// Per-element symmetric stiffness matrices kept for a matrix-free Hessian product: the upper
// 3x3 blocks K_ab (a <= b) of each element in single precision (a hexahedron: 36 blocks, 1,296
// bytes, against ~4 kB per hexahedron for the assembled double matrix with its indices), stored
// as one column panel per node b (rows 0 .. 3b + 2 of columns 3b .. 3b + 2, column-major), so a
// product is a few short contiguous matrix-vector products per element.
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

  // Stores block K_ab (a <= b, node indices within element e) in single precision, and reads it.
  void store(Eigen::Index e, int a, int b, const Mat3& K);
  Mat3 block(Eigen::Index e, int a, int b) const;

  // y += K x over all elements (x and y in the mesh's global DOF numbering).
  void add_product(const Eigen::VectorXd& x, Eigen::VectorXd& y) const;
  // Element e's whole symmetric matrix (3 nodes x 3 nodes, node order of the element) into the
  // top-left corner of K, in double.
  void unpack(Eigen::Index e, Eigen::Ref<Eigen::MatrixXd> K) const;
  // diagonal[v] += sum over elements of the vertex's diagonal blocks.
  void add_diagonal(std::vector<Mat3>& diagonal) const;
  std::size_t bytes() const { return values_.size() * sizeof(float); }

 private:
  const Discretization* d_ = nullptr;
  int nodes_ = 0;
  std::size_t per_element_ = 0;  // floats per element: 9 nodes (nodes + 1) / 2
  std::vector<float> values_;  // per element, its column panels
};

}  // namespace sinew
