#include "sinew/element/element_rule.hpp"

#include <cmath>

namespace sinew {
namespace {

// Reference corner signs in VTK_HEXAHEDRON order.
constexpr int kHexCorner[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                  {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};

QuadratureRule make_hex_rule() {
  QuadratureRule rule;
  const double g = 1.0 / std::sqrt(3.0);
  for (int q = 0; q < 8; ++q) {
    const Eigen::Vector3d xi(kHexCorner[q][0] * g, kHexCorner[q][1] * g, kHexCorner[q][2] * g);
    Eigen::MatrixX3d d(8, 3);
    for (int a = 0; a < 8; ++a) {
      const double sx = kHexCorner[a][0], sy = kHexCorner[a][1], sz = kHexCorner[a][2];
      // N_a = (1 + sx xi)(1 + sy eta)(1 + sz zeta) / 8
      d(a, 0) = 0.125 * sx * (1 + sy * xi.y()) * (1 + sz * xi.z());
      d(a, 1) = 0.125 * sy * (1 + sx * xi.x()) * (1 + sz * xi.z());
      d(a, 2) = 0.125 * sz * (1 + sx * xi.x()) * (1 + sy * xi.y());
    }
    rule.dN_dxi.push_back(d);
    rule.weights.push_back(1.0);
  }
  return rule;
}

QuadratureRule make_tet_rule() {
  QuadratureRule rule;
  Eigen::MatrixX3d d(4, 3);
  d << -1, -1, -1,
        1,  0,  0,
        0,  1,  0,
        0,  0,  1;
  rule.dN_dxi.push_back(d);
  rule.weights.push_back(1.0 / 6.0);
  return rule;
}

}  // namespace

const QuadratureRule& quadrature_rule(ElementKind kind) {
  static const QuadratureRule hex = make_hex_rule();
  static const QuadratureRule tet = make_tet_rule();
  return kind == ElementKind::Hex8 ? hex : tet;
}

Eigen::Matrix<double, 8, 1> hex_shape_functions(const Eigen::Vector3d& xi) {
  Eigen::Matrix<double, 8, 1> n;
  for (int a = 0; a < 8; ++a) {
    n(a) = 0.125 * (1 + kHexCorner[a][0] * xi.x()) * (1 + kHexCorner[a][1] * xi.y()) *
           (1 + kHexCorner[a][2] * xi.z());
  }
  return n;
}

}  // namespace sinew
