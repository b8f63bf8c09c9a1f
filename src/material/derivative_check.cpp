#include "sinew/material/derivative_check.hpp"

#include <algorithm>
#include <cmath>

#include "sinew/core/finite_difference.hpp"
#include "sinew/core/svd.hpp"

namespace sinew {

namespace {
Mat3 unit(int k) {
  Mat3 E = Mat3::Zero();
  E(k % 3, k / 3) = 1.0;  // column-wise vec order
  return E;
}
}  // namespace

double material_difference_step(const Mat3& F) {
  const Vec3 s = signed_svd(F).sigma;
  double reach = std::min(1.0, s.cwiseAbs().minCoeff());
  for (int i = 0; i < 3; ++i)
    for (int j = i + 1; j < 3; ++j) reach = std::min(reach, std::abs(s(i) + s(j)));
  return 1e-3 * reach;
}

Mat3 difference_pk1(const Material& m, const Mat3& F, double step) {
  const double h = step > 0.0 ? step : material_difference_step(F);
  auto psi = [&](const Mat3& G) { return m.psi(G); };
  Mat3 P;
  for (int k = 0; k < 9; ++k) P(k % 3, k / 3) = richardson_difference(psi, F, unit(k), h);
  return P;
}

Mat9 difference_hessian(const Material& m, const Mat3& F, double step) {
  const double h = step > 0.0 ? step : material_difference_step(F);
  auto P = [&](const Mat3& G) { return vec(m.pk1(G)); };
  Mat9 H;
  for (int k = 0; k < 9; ++k) H.col(k) = richardson_difference(P, F, unit(k), h);
  return H;
}

double relative_difference(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, double floor) {
  return (a - b).norm() / std::max(b.norm(), floor);
}

MaterialDerivativeCheck check_material_derivatives(const Material& m, const Mat3& F) {
  MaterialDerivativeCheck c;
  c.step = material_difference_step(F);
  const Mat9 H_fd = difference_hessian(m, F, c.step);
  const double modulus = std::max(H_fd.norm(), 1e-300);
  c.pk1_error = relative_difference(m.pk1(F), difference_pk1(m, F, c.step), 1e-4 * modulus);
  c.hessian_error = relative_difference(m.hessian(F), H_fd, 1e-300);
  return c;
}

}  // namespace sinew
