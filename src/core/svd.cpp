#include "sinew/core/svd.hpp"

#include <Eigen/SVD>

namespace sinew {

SignedSvd signed_svd(const Mat3& F) {
  Eigen::JacobiSVD<Mat3> svd(F, Eigen::ComputeFullU | Eigen::ComputeFullV);
  SignedSvd out{svd.matrixU(), svd.matrixV(), svd.singularValues()};
  // Eigen sorts singular values descending, so column 2 holds the smallest.
  if (out.U.determinant() < 0.0) {
    out.U.col(2) *= -1.0;
    out.sigma(2) *= -1.0;
  }
  if (out.V.determinant() < 0.0) {
    out.V.col(2) *= -1.0;
    out.sigma(2) *= -1.0;
  }
  return out;
}

Mat3 polar_rotation(const Mat3& F) {
  const SignedSvd s = signed_svd(F);
  return s.U * s.V.transpose();
}

Mat3 cofactor(const Mat3& F) {
  Mat3 g;
  g.col(0) = F.col(1).cross(F.col(2));
  g.col(1) = F.col(2).cross(F.col(0));
  g.col(2) = F.col(0).cross(F.col(1));
  return g;
}

Mat3 cross_matrix(const Vec3& x) {
  Mat3 m;
  m << 0.0, -x(2), x(1),
       x(2), 0.0, -x(0),
      -x(1), x(0), 0.0;
  return m;
}

Mat9 volume_hessian(const Mat3& F) {
  // Block (i, j) is d(dJ/df_i)/df_j; the macro structure is itself a cross-product matrix.
  Mat9 H = Mat9::Zero();
  const Mat3 f0 = cross_matrix(F.col(0));
  const Mat3 f1 = cross_matrix(F.col(1));
  const Mat3 f2 = cross_matrix(F.col(2));
  H.block<3, 3>(0, 3) = -f2;
  H.block<3, 3>(0, 6) = f1;
  H.block<3, 3>(3, 0) = f2;
  H.block<3, 3>(3, 6) = -f0;
  H.block<3, 3>(6, 0) = -f1;
  H.block<3, 3>(6, 3) = f0;
  return H;
}

}  // namespace sinew
