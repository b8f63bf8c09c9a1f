#pragma once
// The projected stiffness of a trilinear hexahedron (8 nodes, 8 quadrature points) for a
// material written in the invariants I_C and J, with the element's 8 quadrature points in SIMD
// lanes. Per point the Hessian is the closed form
//   H = 2 Psi_I I + 4 Psi_II f f^T + 2 Psi_IJ (f g^T + g f^T) + Psi_JJ g g^T + Psi_J d2J/dF2
// (f = vec F, g = vec cof F; paper 000 Eq. 41 and §5.3), and a projection only adds
// (new - old eigenvalue) q q^T for the modes it changes: twist and flip modes with eigenvalues
// 2 Psi_I +- Psi_J sigma_k, scaling modes from the 3x3 block in sigma (paper 000 §4.3-4.6).
// The SVD and the 3x3 eigensystem are the batched Jacobi ones (core/batched_eigen3.hpp);
// B^T H B runs with the nodes in the lanes. Same result as the generic path
// (material.projected_hessian + fixed_element::add_stiffness) to rounding.
#include <Eigen/Core>

#include "sinew/element/discretization.hpp"
#include "sinew/element/fixed_element.hpp"
#include "sinew/material/material.hpp"

namespace sinew {

// dN/dX and weights of a hexahedron's 8 quadrature points in the two layouts the kernel reads.
struct HexGradientLanes {
  double point_lanes[8][3][8];  // [a][k][q] = dN_a/dX_k at point q
  double node_lanes[8][3][8];   // [q][k][a], the same numbers
  double weight[8];
};
HexGradientLanes hex_gradient_lanes(const Discretization& d, Eigen::Index e);

// K[a][b] += the element's projected Hessian blocks (a <= b) at node positions xe. Returns
// false, with K unchanged, when a quadrature point's F is not finite or outside the material's
// domain; the caller's generic path then reports it.
bool add_hex_invariant_stiffness(const InvariantMaterial& material, Projection mode, const HexGradientLanes& D,
                                 const fixed_element::Positions<8>& xe, fixed_element::SymmetricBlocks<8>& K);

// The same for two elements in one call (16 lanes in the point stages, so one element's
// latency-bound SVD sweeps overlap the other's); each K is bitwise what the single call gives.
// Returns false, with both K unchanged, when either element has a bad point.
bool add_hex_invariant_stiffness_pair(const InvariantMaterial& material, Projection mode,
                                      const HexGradientLanes& D0, const fixed_element::Positions<8>& x0,
                                      fixed_element::SymmetricBlocks<8>& K0, const HexGradientLanes& D1,
                                      const fixed_element::Positions<8>& x1, fixed_element::SymmetricBlocks<8>& K1);

}  // namespace sinew
