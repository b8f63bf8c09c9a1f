#pragma once
// Per-element stress tensors of a state, volume-averaged over each element's quadrature points:
// the first Piola-Kirchhoff stress P(F) and the Cauchy stress sigma = P F^T / J. One row per
// element holding the tensor's entries row by row (T(0,0), T(0,1), ..., T(2,2)), the layout of
// an (elements, 3, 3) C-ordered array.
#include <Eigen/Core>

#include "sinew/model/model.hpp"

namespace sinew {

using TensorRows = Eigen::Matrix<double, Eigen::Dynamic, 9, Eigen::RowMajor>;

struct ElementStresses {
  TensorRows pk1, cauchy;
};

// Needs the scene's hyperelastic material (sinew::Error for the energy-limited corotational
// model, whose elements have no material). At a quadrature point with J = 0 the Cauchy stress is
// not finite.
ElementStresses element_stresses(const Model& model, const Eigen::VectorXd& x);

}  // namespace sinew
