#pragma once
// Fixed-size element kernels for an element of N nodes (8: trilinear hexahedron, 4: linear
// tetrahedron): node positions, F = x_e D, the gradient term P D^T and the stiffness term
// B^T H B on the stack, so the element loops of assembly neither allocate nor call a general
// matrix product. Same arithmetic as add_element_hessian (discretization.hpp), which stays for
// elements of any size.
#include <Eigen/Core>

#include "sinew/core/types.hpp"
#include "sinew/element/discretization.hpp"

namespace sinew::fixed_element {

template <int N>
using Gradients = Eigen::Matrix<double, N, 3>;  // dN/dX at one quadrature point
template <int N>
using Positions = Eigen::Matrix<double, 3, N>;  // node positions as columns

// Node positions of element e from the DOF vector x.
template <int N>
Positions<N> positions(const Discretization& d, Eigen::Index e, const Eigen::VectorXd& x) {
  Positions<N> xe(3, d.nodes());  // (N may be Eigen::Dynamic: then any node count)
  const auto& elements = d.mesh().elements;
  for (int a = 0; a < d.nodes(); ++a) xe.col(a) = x.segment<3>(3 * elements(e, a));
  return xe;
}

// dN/dX of quadrature point q of element e as a fixed-size map onto the discretisation's storage.
template <int N>
Eigen::Map<const Gradients<N>> gradients(const Discretization& d, Eigen::Index e, int q) {
  return Eigen::Map<const Gradients<N>>(d.gradients(e, q).data(), d.nodes(), 3);
}

// The upper node-pair blocks of a symmetric element matrix: K[a][b] for a <= b.
template <int N>
struct SymmetricBlocks {
  Mat3 K[N][N];
  void set_zero() {
    for (int a = 0; a < N; ++a)
      for (int b = a; b < N; ++b) K[a][b].setZero();
  }
  // The diagonal blocks are symmetric up to round-off; make them exactly so.
  void symmetrize_diagonal() {
    for (int a = 0; a < N; ++a) K[a][a] = (0.5 * (K[a][a] + K[a][a].transpose())).eval();
  }
};

// K(a, b) += w sum_kl D(a,k) H_kl D(b,l) for a <= b, with H_kl the 3x3 block H(3k+i, 3l+j)
// (dF/dx^T H dF/dx restricted to one quadrature point; see add_element_hessian).
template <int N>
void add_stiffness(const Eigen::Map<const Gradients<N>>& D, const Mat9& H, double w, SymmetricBlocks<N>& K) {
  // T = H B: column 3b+j is sum_l H(:, 3l+j) D(b,l).
  Eigen::Matrix<double, 9, 3 * N> T;
  for (int b = 0; b < N; ++b)
    for (int j = 0; j < 3; ++j)
      T.col(3 * b + j) = H.col(j) * D(b, 0) + H.col(3 + j) * D(b, 1) + H.col(6 + j) * D(b, 2);
  T *= w;
  for (int a = 0; a < N; ++a)
    for (int b = a; b < N; ++b)
      K.K[a][b].noalias() += D(a, 0) * T.template block<3, 3>(0, 3 * b) + D(a, 1) * T.template block<3, 3>(3, 3 * b) +
                             D(a, 2) * T.template block<3, 3>(6, 3 * b);
}

}  // namespace sinew::fixed_element
