#pragma once
#include "sinew/core/types.hpp"

namespace sinew {

// Rotation-variant SVD F = U diag(sigma) V^T (paper 000 Eq. 2): U and V are proper
// rotations, and a reflection is moved into the smallest singular value, which may
// then be negative.
struct SignedSvd {
  Mat3 U;
  Mat3 V;
  Vec3 sigma;
};

SignedSvd signed_svd(const Mat3& F);

// Polar decomposition F = R S with R a rotation (from the rotation-variant SVD).
Mat3 polar_rotation(const Mat3& F);

// dJ/dF, the cofactor matrix, as cross products of F's columns (paper 000 Eq. 19).
Mat3 cofactor(const Mat3& F);

// The volume Hessian d^2J/dF^2 in column-wise vec form (paper 000 Eq. 28).
Mat9 volume_hessian(const Mat3& F);

// 3x3 cross-product matrix hat(x) with hat(x) y = x × y.
Mat3 cross_matrix(const Vec3& x);

}  // namespace sinew
