#pragma once
// A symmetric matrix of 3x3 vertex blocks given as a sum of small dense element matrices,
// A = sum_e S_e^T K_e S_e (S_e picks element e's vertices): how a matrix-free operator shows its
// content to a preconditioner that needs more than products (multigrid's Galerkin coarse
// operator, linalg/element_galerkin.hpp).
#include <Eigen/Core>
#include <cstdint>

namespace sinew {

inline constexpr int kMaxElementMatrixVertices = 8;
using ElementMatrix = Eigen::Matrix<double, 3 * kMaxElementMatrixVertices, 3 * kMaxElementMatrixVertices>;

class ElementMatrices {
 public:
  virtual ~ElementMatrices() = default;
  virtual Eigen::Index count() const = 0;
  // Element e's vertices (at most kMaxElementMatrixVertices) into `vertices`; returns how many.
  virtual int vertices(Eigen::Index e, int* vertices) const = 0;
  // Element e's symmetric matrix in the top-left 3n x 3n corner of K (n = vertices(e)), its
  // vertices in the same order. Safe to call from several threads at once.
  virtual void matrix(Eigen::Index e, ElementMatrix& K) const = 0;
  // Changes whenever the elements or their vertices change (a symbolic product made for one id
  // is valid for every matrix with the same id).
  virtual std::uint64_t structure_id() const = 0;
};

}  // namespace sinew
