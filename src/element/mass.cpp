#include "sinew/element/mass.hpp"

#include <fmt/format.h>
#include <vector>

#include "sinew/core/error.hpp"
#include "sinew/element/element_rule.hpp"

namespace sinew {
namespace {

// Shape function values at the quadrature points of the rule.
std::vector<Eigen::VectorXd> shape_values(ElementKind kind) {
  std::vector<Eigen::VectorXd> out;
  if (kind == ElementKind::Hex8) {
    const double g = 1.0 / std::sqrt(3.0);
    constexpr int kSign[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                 {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
    for (const auto& s : kSign) out.push_back(hex_shape_functions(Eigen::Vector3d(s[0] * g, s[1] * g, s[2] * g)));
  }
  return out;
}

void check_density(double density) {
  if (!std::isfinite(density) || !(density > 0.0))
    throw Error(fmt::format("must be a positive finite number, got {}", density), "density");
}

}  // namespace

Eigen::VectorXd lumped_mass(const Discretization& disc, double density) {
  check_density(density);
  const auto& elements = disc.mesh().elements;
  Eigen::VectorXd m = Eigen::VectorXd::Zero(disc.mesh().num_vertices());
  for (Eigen::Index e = 0; e < disc.num_elements(); ++e) {
    // Row sums of N_a N_b integrate N_a (partition of unity): lumped mass = rho * integral N_a.
    if (disc.mesh().kind == ElementKind::Tet4) {
      for (int a = 0; a < 4; ++a) m(elements(e, a)) += density * disc.rest_volume(e) / 4.0;
    } else {
      const auto N = shape_values(ElementKind::Hex8);
      for (int q = 0; q < disc.quadrature_points(); ++q)
        for (int a = 0; a < 8; ++a) m(elements(e, a)) += density * disc.weight(e, q) * N[q](a);
    }
  }
  return m;
}

Eigen::SparseMatrix<double> consistent_mass(const Discretization& disc, double density) {
  check_density(density);
  const auto& elements = disc.mesh().elements;
  const int n = disc.nodes();
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(static_cast<size_t>(disc.num_elements()) * n * n * 3);
  const auto N = shape_values(ElementKind::Hex8);
  for (Eigen::Index e = 0; e < disc.num_elements(); ++e) {
    Eigen::MatrixXd Me = Eigen::MatrixXd::Zero(n, n);
    if (disc.mesh().kind == ElementKind::Tet4) {
      // Exact: integral N_a N_b = V (1 + delta_ab) / 20.
      Me.setConstant(disc.rest_volume(e) / 20.0);
      Me.diagonal().array() *= 2.0;
    } else {
      for (int q = 0; q < disc.quadrature_points(); ++q) Me += disc.weight(e, q) * N[q] * N[q].transpose();
    }
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < n; ++b)
        for (int i = 0; i < 3; ++i)
          triplets.emplace_back(3 * elements(e, a) + i, 3 * elements(e, b) + i, density * Me(a, b));
  }
  Eigen::SparseMatrix<double> M(disc.num_dofs(), disc.num_dofs());
  M.setFromTriplets(triplets.begin(), triplets.end());
  return M;
}

}  // namespace sinew
