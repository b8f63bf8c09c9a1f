#pragma once
// Corotational linear hexahedra (paper 001 §3): Hookean stiffness K_e integrated by 2x2x2 Gauss
// (Eq. 10), one rotation per element from the polar decomposition of the deformation gradient
// of the hexahedron's innermost tetrahedron (Fig. 2), stiffness warped as R K_e R^T.
#include <vector>

#include "sinew/forms/element_energy_model.hpp"
#include "sinew/material/lame.hpp"

namespace sinew {

// Coefficients of the isotropic material matrix (paper 001 §4.2): E1 = Y(1-nu)/((1+nu)(1-2nu)),
// E2 = Y nu/((1+nu)(1-2nu)), E3 = Y/(2(1+nu)), i.e. lambda + 2 mu, lambda and mu.
struct HookeCoefficients {
  double E1 = 0.0, E2 = 0.0, E3 = 0.0;
  static HookeCoefficients from_young_poisson(double young, double poisson);
};

// The innermost tetrahedron of the 5-tetrahedron (alternating-corner) subdivision of a
// VTK-ordered hexahedron: the regular tetrahedron on corners 0, 2, 5, 7, which touches every
// face of the hexahedron and so sees all of its deformation modes.
inline constexpr int kInnermostTet[4] = {0, 2, 5, 7};

class CorotationalHex final : public ElementEnergyModel {
 public:
  CorotationalHex(std::shared_ptr<const Discretization> disc, HookeCoefficients coefficients);

  std::string name() const override { return "corotational-hex"; }
  const Discretization& discretization() const override { return *disc_; }
  const HookeCoefficients& coefficients() const { return c_; }

  // R_e from the polar decomposition of the innermost tetrahedron's F.
  Mat3 rotation(Eigen::Index e, const Eigen::VectorXd& x) const;
  // Rest-frame stiffness K_e (24 x 24, node-major), Eq. 10.
  const Eigen::MatrixXd& element_stiffness(Eigen::Index e) const { return K_[e]; }

  // U_e = sum_q w_q psi(eps_q), eps = sym(R^T G - I) (Eq. 11, 13), psi = 1/2 eps : C : eps.
  double element_energy(Eigen::Index e, const Eigen::VectorXd& x) const override;
  Eigen::VectorXd element_energy_gradient(Eigen::Index e, const Eigen::VectorXd& x,
                                          JacobianKind kind) const override;
  bool supports(JacobianKind) const override { return true; }
  // R K_e R^T (the rotation's change neglected, as in the warped stiffness).
  Eigen::MatrixXd element_energy_hessian(Eigen::Index e, const Eigen::VectorXd& x) const override;

  // f = -sum_e R K_e (R^T x_e - X_e) and K = sum_e R K_e R^T (the usual warped stiffness).
  Eigen::VectorXd forces(const Eigen::VectorXd& x) const override;
  Eigen::SparseMatrix<double> stiffness(const Eigen::VectorXd& x) const override;
  // One rotation per element for both (what a time step needs at its start).
  void forces_and_stiffness(const Eigen::VectorXd& x, Eigen::VectorXd& f, Eigen::SparseMatrix<double>& K) const override;

 private:
  std::shared_ptr<const Discretization> disc_;
  HookeCoefficients c_;
  std::vector<Eigen::MatrixXd> K_;
  Eigen::VectorXd rest_;  // rest positions X
  // The stiffness pattern, built once, and per element the value slot of each of its 24 x 24
  // entries (column-major), so assembling R K_e R^T is a scatter without sorting.
  Eigen::SparseMatrix<double> pattern_;
  std::vector<std::vector<int>> slots_;
  std::vector<Mat3> tet_rest_inverse_;  // (X_2 - X_0, X_5 - X_0, X_7 - X_0)^-1 per element
};

}  // namespace sinew
