#pragma once
// Element kinematics apart from materials (SOFA style): reference shape-function gradients
// and quadrature for each element kind.
#include <Eigen/Core>
#include <vector>

#include "sinew/mesh/volume_mesh.hpp"

namespace sinew {

struct QuadratureRule {
  // Per quadrature point: reference gradients dN_a/dxi (nodes x 3) and the weight.
  std::vector<Eigen::MatrixX3d> dN_dxi;
  std::vector<double> weights;
};

// Hex8: 2x2x2 Gauss points at ±1/sqrt(3) on [-1,1]^3, unit weights (paper 001 §3.2).
// Tet4: one point (constant gradients), weight 1/6 on the unit reference tetrahedron.
const QuadratureRule& quadrature_rule(ElementKind kind);

// Trilinear shape function values at a reference point (for embedding and output).
Eigen::Matrix<double, 8, 1> hex_shape_functions(const Eigen::Vector3d& xi);

}  // namespace sinew
