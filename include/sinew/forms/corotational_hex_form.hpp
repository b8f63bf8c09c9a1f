#pragma once
// Corotational linear hexahedra (paper 001 §3) as a form: Hookean stiffness K_e integrated by
// 2x2x2 Gauss (Eq. 10), one rotation per element from the polar decomposition of the deformation
// gradient of the hexahedron's innermost tetrahedron (Fig. 2), stiffness warped as R K_e R^T.
// As in corotational FEM (and paper 001 Eq. 17), the form's gradient is the warped elastic force
// and its Hessian the warped stiffness: both hold the rotation fixed, so they are not the exact
// derivatives of the energy (exact_derivatives() is false); the exact element gradient is
// element_gradient(e, x, JacobianKind::Exact).
#include <array>
#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

#include "sinew/forms/element_form.hpp"
#include "sinew/forms/element_rotation_cache.hpp"
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

class CorotationalHexForm final : public ElementForm {
 public:
  CorotationalHexForm(std::shared_ptr<const Discretization> disc, HookeCoefficients coefficients);

  std::string name() const override { return "corotational-hex"; }
  const Discretization& discretization() const override { return *disc_; }
  const HookeCoefficients& coefficients() const { return c_; }

  // R_e from the polar decomposition of the innermost tetrahedron's F.
  Mat3 rotation(Eigen::Index e, const Eigen::VectorXd& x) const { return element_rotation(e, x).R; }
  // Every element's U_e(x) into `energies` (one rotation pass, kept for the per-element calls
  // at the same x that usually follow: constraint Jacobians, element Hessians).
  void element_values(const Eigen::VectorXd& x, std::vector<double>& energies) const override;
  // Rest-frame stiffness K_e (24 x 24, node-major), Eq. 10.
  using ElementMatrix = Eigen::Matrix<double, 24, 24>;
  using ElementVector = Eigen::Matrix<double, 24, 1>;
  const ElementMatrix& element_stiffness(Eigen::Index e) const { return K_[static_cast<size_t>(e)]; }
  // The node pairs (a, b), a <= b, of an element's blocks: pair p is (pair_nodes[p][0],
  // pair_nodes[p][1]), column node b ascending, then a.
  static constexpr int kNodePairs = 36;
  static const std::array<std::array<int, 2>, kNodePairs>& pair_nodes();
  // R K_ab R^T for every node pair p (the blocks above and on the diagonal of R K_e R^T):
  // entry (i, j) of pair p's block at rotated[kNodePairs * (3 i + j) + p]; the same values as
  // R * K_ab * R^T with Eigen's 3x3 products, computed for all pairs at once.
  void rotated_pair_blocks(Eigen::Index e, const Mat3& R, double* rotated) const;

  // U_e = sum_q w_q psi(eps_q), eps = sym(R^T G - I) (Eq. 11, 13), psi = 1/2 eps : C : eps.
  double element_value(Eigen::Index e, const Eigen::VectorXd& x) const override;
  Eigen::VectorXd element_gradient(Eigen::Index e, const Eigen::VectorXd& x, JacobianKind kind) const override;
  bool supports(JacobianKind) const override { return true; }
  // R K_e R^T (the rotation's change neglected, as in the warped stiffness).
  Eigen::MatrixXd element_hessian(Eigen::Index e, const Eigen::VectorXd& x) const override;
  // The same, from the node-pair blocks straight into He (24 x 24).
  void element_hessian_into(Eigen::Index e, const Eigen::VectorXd& x, Eigen::MatrixXd& He) const override;

  // Form: E = sum_e U_e; gradient sum_e R K_e (R^T x_e - X_e) (the warped force, Eq. 17);
  // Hessian sum_e R K_e R^T.
  double value(const Eigen::VectorXd& x) const override;
  void add_gradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const override;
  void add_hessian(const Eigen::VectorXd& x, BlockHessian& H) const override;
  bool exact_derivatives() const override { return false; }

 private:
  std::shared_ptr<const Discretization> disc_;
  HookeCoefficients c_;
  std::vector<ElementMatrix> K_;
  // K_e's pair blocks by lanes: entry (k, l) of pair p at [kNodePairs * (9 e + 3 k + l) + p],
  // so that a rotation's products run over all pairs with contiguous loads.
  std::vector<double> pair_blocks_;
  Eigen::VectorXd rest_;                // rest positions X
  std::vector<Mat3> tet_rest_inverse_;  // (X_2 - X_0, X_5 - X_0, X_7 - X_0)^-1 per element
  // The rotations of the last positions a whole-mesh pass saw (value, gradient, Hessian,
  // element_values); per-element calls at the same positions reuse them.
  std::unique_ptr<ElementRotationCache> rotations_;
  // Per element and node pair (b, a): the slot of block (a, b) in the Hessian pattern of the
  // given id, found once instead of a search per block and assembly.
  const std::vector<int>& scatter_map(const BlockHessian& H) const;
  mutable std::mutex scatter_mutex_;
  mutable std::uint64_t scatter_pattern_ = 0;
  mutable std::vector<int> scatter_slots_;
  ElementRotationCache::Corners corners(Eigen::Index e, const Eigen::VectorXd& x) const;
  // From the corners; `warm` (a rotation of the element at other corners, or null) starts a
  // Newton iteration, with the SVD as fallback.
  ElementRotation compute_rotation(Eigen::Index e, const ElementRotationCache::Corners& c,
                                   const ElementRotation* warm) const;
  ElementRotation element_rotation(Eigen::Index e, const Eigen::VectorXd& x) const;
  std::shared_ptr<const std::vector<ElementRotation>> all_rotations(const Eigen::VectorXd& x) const;
  double element_value(Eigen::Index e, const Eigen::VectorXd& x, const Mat3& R) const;
  // R f_a over the element's nodes (the warped force from the rest-frame one).
  static ElementVector warped_gradient(const Mat3& R, const ElementVector& f);
  // d_a = R^T x_a - X_a over the element's nodes.
  ElementVector unrotated_displacements(Eigen::Index e, const Eigen::VectorXd& x, const Mat3& R) const;
  Eigen::VectorXd element_gradient(Eigen::Index e, const Eigen::VectorXd& x, JacobianKind kind,
                                   const ElementRotation& rotation) const;
};

}  // namespace sinew
