#include "sinew/element/continuum_fields.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "sinew/core/error.hpp"

namespace sinew {
namespace {

// Row-major, so a 9-component array reads as the tensor's rows (ParaView's convention).
void store(const Mat3& A, Eigen::VectorXd& out, Eigen::Index e) {
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) out(9 * e + 3 * r + c) = A(r, c);
}

}  // namespace

Mat3 cauchy_stress(const Mat3& F, const Mat3& P) { return P * F.transpose() / F.determinant(); }

double von_mises_stress(const Mat3& sigma) {
  const Mat3 s = sigma - sigma.trace() / 3.0 * Mat3::Identity();
  return std::sqrt(1.5 * s.cwiseProduct(s).sum());
}

Vec3 principal_stretches(const Mat3& F) {
  // Eigenvalues of C = F^T F are the squared singular values (ascending).
  const Vec3 c = symmetric_eigen3(F.transpose() * F).eigenvalues();
  return Vec3(std::sqrt(std::max(c(2), 0.0)), std::sqrt(std::max(c(1), 0.0)), std::sqrt(std::max(c(0), 0.0)));
}

ContinuumFields continuum_fields(const Discretization& d, const Material* material, const Eigen::VectorXd& x) {
  const Eigen::Index m = d.num_elements();
  if (x.size() != d.num_dofs())
    throw Error(fmt::format("positions have {} values, expected {}", x.size(), d.num_dofs()), "continuum fields");
  ContinuumFields f;
  f.J.resize(m);
  f.principal_stretches.resize(3 * m);
  f.green_lagrange.resize(9 * m);
  if (material) {
    f.cauchy.resize(9 * m);
    f.von_mises.resize(m);
  }
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, m, 256), [&](const auto& r) {
    for (Eigen::Index e = r.begin(); e != r.end(); ++e) {
      const Eigen::Matrix3Xd xe = d.element_positions(e, x);
      double volume = 0.0, J = 0.0, mises = 0.0;
      Vec3 stretches = Vec3::Zero();
      Mat3 E = Mat3::Zero(), sigma = Mat3::Zero();
      for (int q = 0; q < d.quadrature_points(); ++q) {
        const Mat3 F = xe * d.gradients(e, q);
        const double w = d.weight(e, q), det = F.determinant();
        volume += w;
        J += w * det;
        stretches += w * principal_stretches(F);
        E += w * 0.5 * (F.transpose() * F - Mat3::Identity());
        if (!material) continue;
        if (det == 0.0 || !material->in_domain(F)) {
          sigma.setConstant(nan);
          mises = nan;
          continue;
        }
        const Mat3 s = cauchy_stress(F, material->pk1(F));
        sigma += w * s;
        mises += w * von_mises_stress(s);
      }
      f.J(e) = J / volume;
      f.principal_stretches.segment<3>(3 * e) = stretches / volume;
      store(E / volume, f.green_lagrange, e);
      if (material) {
        store(sigma / volume, f.cauchy, e);
        f.von_mises(e) = mises / volume;
      }
    }
  });
  return f;
}

Eigen::VectorXd average_to_vertices(const Discretization& d, const Eigen::VectorXd& values, int components) {
  const VolumeMesh& mesh = d.mesh();
  if (components < 1 || values.size() != components * mesh.num_elements())
    throw Error(fmt::format("element field has {} values, expected {} x {} elements", values.size(), components,
                            mesh.num_elements()),
                "vertex average");
  Eigen::VectorXd sum = Eigen::VectorXd::Zero(components * mesh.num_vertices());
  Eigen::VectorXd weight = Eigen::VectorXd::Zero(mesh.num_vertices());
  for (Eigen::Index e = 0; e < mesh.num_elements(); ++e) {
    const double V = d.rest_volume(e);
    for (Eigen::Index a = 0; a < mesh.elements.cols(); ++a) {
      const int v = mesh.elements(e, a);
      sum.segment(components * v, components) += V * values.segment(components * e, components);
      weight(v) += V;
    }
  }
  for (Eigen::Index v = 0; v < mesh.num_vertices(); ++v)
    if (weight(v) > 0.0) sum.segment(components * v, components) /= weight(v);
  return sum;
}

}  // namespace sinew
