#include "sinew/element/mesh_validation.hpp"

#include <Eigen/Dense>
#include <fmt/format.h>

#include "sinew/core/error.hpp"
#include "sinew/element/element_rule.hpp"

namespace sinew {

void validate_mesh(const VolumeMesh& mesh, const std::string& source) {
  mesh.validate(source);
  const int n = nodes_per_element(mesh.kind);
  const QuadratureRule& rule = quadrature_rule(mesh.kind);
  Eigen::MatrixX3d X(n, 3);
  for (Eigen::Index e = 0; e < mesh.num_elements(); ++e) {
    for (int a = 0; a < n; ++a) X.row(a) = mesh.vertices.row(mesh.elements(e, a));
    for (const auto& d : rule.dN_dxi) {
      const double det = (X.transpose() * d).determinant();  // dX/dxi
      if (!(det > 0.0)) {
        throw Error(fmt::format("element {} is inverted or degenerate (rest Jacobian {:.3g})", e, det), source);
      }
    }
  }
}

}  // namespace sinew
