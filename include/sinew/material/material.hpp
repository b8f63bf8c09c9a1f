#pragma once
// One interface for every isotropic hyperelastic energy density Psi(F).
//
// Every material exposes two views of the same energy:
//  * the F view: Psi, P = dPsi/dF and the 9x9 Hessian d^2Psi/dF^2 (column-wise vec,
//    paper 000 §4.1), plus its eigensystem and PSD projection;
//  * the stretch view: psi(sigma), its gradient (principal PK1 stresses) and its 3x3
//    Hessian in the signed singular values of F (rotation-variant SVD).
// Stretch-based materials (StretchMaterial) implement the stretch view and get the F view
// from the analytic eigensystem; invariant-based materials (InvariantMaterial) implement
// Psi(I_C, J) and get both views from the invariant derivatives.
#include <Eigen/Eigenvalues>
#include <string>

#include "sinew/core/svd.hpp"
#include "sinew/core/types.hpp"

namespace sinew {

// How a Hessian is made positive semi-definite.
enum class Projection {
  Clamp,  // negative eigenvalues -> 0 (default)
  Abs,    // eigenvalues -> |eigenvalue|
  None,   // the true Hessian
};
Projection parse_projection(const std::string& text);  // "clamp" | "abs" | "none"
const char* to_string(Projection p);

// Where the energy is defined.
enum class Domain {
  All,        // every F, including inverted and degenerate ones
  PositiveJ,  // J > 0 only (log- or power-based energies); inverted F is an error
};

// Nine eigenpairs of the F-space Hessian. Columns of `vectors` are vec(Q_k), orthonormal.
// Ordering: k = 0..2 the "scaling" modes (U diag(q) V^T from the 3x3 stretch block),
// k = 3..5 twist modes of pairs (1,2), (0,2), (0,1), k = 6..8 the matching flip modes.
struct Eigensystem {
  Vec9 values;
  Mat9 vectors;
  Mat9 reconstruct() const;                    // sum_k values_k v_k v_k^T
  Mat9 projected(Projection mode, double floor = 0.0) const;
};

// Everything a solver needs from one F, computed with one SVD.
struct Evaluation {
  double psi = 0.0;
  Mat3 P = Mat3::Zero();
  Mat9 hessian = Mat9::Zero();  // projected as requested
};

class Material {
 public:
  virtual ~Material() = default;

  virtual std::string name() const = 0;
  virtual Domain domain() const { return Domain::All; }

  // ---- F view (public API: checks the domain and throws sinew::Error outside it) ----
  double psi(const Mat3& F) const;
  Mat3 pk1(const Mat3& F) const;
  Mat9 hessian(const Mat3& F) const;
  Eigensystem eigensystem(const Mat3& F) const;
  Mat9 projected_hessian(const Mat3& F, Projection mode = Projection::Clamp) const;
  Evaluation evaluate(const Mat3& F, Projection mode = Projection::Clamp) const;

  bool in_domain(const Mat3& F) const;
  void check_domain(const Mat3& F) const;

  // Eigenvalues below this floor are lifted to it by Projection::Clamp. Zero except for
  // the filtered Neo-Hookean baseline, which keeps PhysBAM's epsilon_p = -1e-4.
  virtual double projection_floor() const { return 0.0; }

  // ---- stretch view: psi(sigma) with sigma the signed singular values ----
  virtual double psi_stretch(const Vec3& sigma) const = 0;
  virtual Vec3 grad_stretch(const Vec3& sigma) const = 0;
  virtual Mat3 hess_stretch(const Vec3& sigma) const = 0;

  // Eigenvalues of the three 2x2 twist/flip blocks. Pair k couples (i, j) = ((k+1)%3, (k+2)%3):
  //   twist_k = (p_i + p_j) / (sigma_i + sigma_j),  flip_k = (p_i - p_j) / (sigma_i - sigma_j),
  // with p = grad_stretch(sigma). The default uses the divided differences and their
  // limits (sigma_i -> ±sigma_j) from hess_stretch, so no division blows up.
  virtual void pair_eigenvalues(const Vec3& sigma, const Vec3& p, const Mat3& h, Vec3& twist,
                                Vec3& flip) const;

 protected:
  // F-view implementations; the defaults go through the rotation-variant SVD.
  virtual double psi_impl(const Mat3& F) const;
  virtual Mat3 pk1_impl(const Mat3& F) const;
  virtual Mat9 hessian_impl(const Mat3& F) const;
  virtual Eigensystem eigensystem_impl(const Mat3& F) const;
  virtual Evaluation evaluate_impl(const Mat3& F, Projection mode) const;

  // The analytic eigensystem from an SVD and the stretch-space derivatives.
  Eigensystem stretch_eigensystem(const SignedSvd& svd, const Vec3& p, const Mat3& h) const;
};

// Eigendecomposition of a symmetric 3x3 block (ascending eigenvalues), accurate also when
// eigenvalues (nearly) coincide.
Eigen::SelfAdjointEigenSolver<Mat3> symmetric_eigen3(const Mat3& A);

// Builds the 9 eigenvectors of an isotropic energy's Hessian from U, V and the 3x3 block's
// eigenvectors (columns of Q). Shared by the generic and the closed-form eigensystems.
Mat9 isotropic_eigenvectors(const SignedSvd& svd, const Mat3& Q);

// A material written directly as psi(sigma_0, sigma_1, sigma_2).
class StretchMaterial : public Material {};

// A material written as Psi(I_C, J) with I_C = tr(F^T F), J = det F (paper 000 §5.3,
// "general model"). Subclasses give Psi and its first and second invariant derivatives.
class InvariantMaterial : public Material {
 public:
  struct Derivatives {
    double psi = 0.0;
    double dI = 0.0, dJ = 0.0;               // dPsi/dI_C, dPsi/dJ
    double dII = 0.0, dIJ = 0.0, dJJ = 0.0;  // second derivatives
  };
  virtual Derivatives invariant_derivatives(double Ic, double J) const = 0;
  // The derivatives without psi (left 0), for callers that need no energy (stresses, Hessians,
  // the batched element kernel); materials whose psi costs a log or exp override it.
  virtual Derivatives curvature_derivatives(double Ic, double J) const { return invariant_derivatives(Ic, J); }
  // curvature_derivatives at n points in one call (an element's quadrature points): element
  // loops pay one virtual call instead of several per point. Same values as point by point.
  virtual void curvature_derivatives_at(int n, const double* Ic, const double* J, Derivatives* out) const {
    for (int i = 0; i < n; ++i) out[i] = curvature_derivatives(Ic[i], J[i]);
  }

  double psi_stretch(const Vec3& sigma) const override;
  Vec3 grad_stretch(const Vec3& sigma) const override;
  Mat3 hess_stretch(const Vec3& sigma) const override;
  // Exact: twist = 2 Psi_I + Psi_J sigma_k, flip = 2 Psi_I - Psi_J sigma_k.
  void pair_eigenvalues(const Vec3& sigma, const Vec3& p, const Mat3& h, Vec3& twist,
                        Vec3& flip) const override;

 protected:
  double psi_impl(const Mat3& F) const override;
  Mat3 pk1_impl(const Mat3& F) const override;
  // Hessian = 2 Psi_I I + 4 Psi_II f f^T + 2 Psi_IJ (f g^T + g f^T) + Psi_JJ g g^T + Psi_J H
  Mat9 hessian_impl(const Mat3& F) const override;
  Eigensystem eigensystem_impl(const Mat3& F) const override;
  Evaluation evaluate_impl(const Mat3& F, Projection mode) const override;

  // Building blocks from one set of derivatives (for subclasses with closed forms).
  static Mat3 stretch_block(const Derivatives& d, const Vec3& sigma);  // 3x3 block in sigma
  static void pair_eigenvalues_from(const Derivatives& d, const Vec3& sigma, Vec3& twist,
                                    Vec3& flip);
  static Eigensystem invariant_eigensystem(const Derivatives& d, const SignedSvd& svd);
  static Mat9 hessian_from(const Derivatives& d, const Mat3& F);
};

}  // namespace sinew
