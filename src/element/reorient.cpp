#include "sinew/element/reorient.hpp"

#include <Eigen/Dense>
#include <utility>

#include "sinew/element/element_rule.hpp"

namespace sinew {

Eigen::Index reorient_inverted_elements(VolumeMesh& mesh) {
  const int n = nodes_per_element(mesh.kind);
  const QuadratureRule& rule = quadrature_rule(mesh.kind);
  Eigen::Index flipped = 0;
  for (Eigen::Index e = 0; e < mesh.num_elements(); ++e) {
    Eigen::MatrixX3d X(n, 3);
    for (int a = 0; a < n; ++a) {
      const int v = mesh.elements(e, a);
      if (v < 0 || v >= mesh.num_vertices()) return flipped;  // validate() names the bad index
      X.row(a) = mesh.vertices.row(v);
    }
    bool all_negative = true;
    for (const auto& d : rule.dN_dxi) all_negative = all_negative && (X.transpose() * d).determinant() < 0.0;
    if (!all_negative) continue;
    if (mesh.kind == ElementKind::Tet4) {
      std::swap(mesh.elements(e, 1), mesh.elements(e, 2));
    } else {
      for (int a = 0; a < 4; ++a) std::swap(mesh.elements(e, a), mesh.elements(e, a + 4));
    }
    ++flipped;
  }
  return flipped;
}

}  // namespace sinew
