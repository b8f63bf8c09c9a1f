#pragma once
// Plain Eigen types at every interface (libigl style).
#include <Eigen/Dense>

namespace sinew {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Vec9 = Eigen::Matrix<double, 9, 1>;
using Mat9 = Eigen::Matrix<double, 9, 9>;

// Column-wise flattening of a 3x3 matrix (paper 000 §4.1): vec(A)[3c + r] = A(r, c).
// Eigen stores matrices column-major, so this is a plain reinterpretation.
inline Vec9 vec(const Mat3& A) { return Eigen::Map<const Vec9>(A.data()); }
inline Mat3 unvec(const Vec9& a) { return Eigen::Map<const Mat3>(a.data()); }

}  // namespace sinew
