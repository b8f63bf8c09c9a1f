#pragma once
// Paper 000 §4.6 and §5.3: the closed-form eigensystem of every energy Psi(I_C, J) without an
// I_C-J coupling term. Its Hessian has the "general model" form (Eq. 52)
//   A = gamma_I I + gamma_F f f^T + gamma_G g g^T + gamma_H H,
// f = vec(F), g = vec(dJ/dF), H = d^2J/dF^2, with
//   gamma_I = 2 Psi_I, gamma_F = 4 Psi_II, gamma_G = Psi_JJ, gamma_H = Psi_J.
// Six eigenpairs are known outright (Eq. 46-48, Appendix A): gamma_I +- gamma_H sigma_k with
// eigenvectors U D_k V^T / sqrt(2). The other three come from the cubic of the rank-two update
// of H (Eq. 42-43) in the 3x3 stretch block
//   gamma_I I + gamma_F s s^T + gamma_G g g^T + gamma_H Hd,  g = (s1 s2, s0 s2, s0 s1).
#include "sinew/material/material.hpp"

namespace sinew {

struct GeneralModelCoefficients {
  double gamma_I = 0.0;
  double gamma_F = 0.0;
  double gamma_G = 0.0;
  double gamma_H = 0.0;
};

// Eq. 42-43 multiplied through by gamma_H^3 so nothing divides by gamma_H = 0 (J = alpha):
// with eps' = eps - gamma_I = gamma_H eps_bar, eta = gamma_F / gamma_H, rho = gamma_G / gamma_H,
//   eps'^3 + a2 eps'^2 + a1 eps' + a0 = 0,   a_k = c_k gamma_H^(3-k).
// Returns (a0, a1, a2).
Vec3 general_model_cubic(const Vec3& sigma, const GeneralModelCoefficients& c);

// Eigenpairs of the 3x3 scaling block: ascending values, orthonormal columns.
struct ScalingBlock {
  Vec3 values;
  Mat3 vectors;
};
ScalingBlock general_model_scaling_block(const Vec3& sigma, const GeneralModelCoefficients& c);

// All nine eigenpairs (scaling block, then twist and flip pairs as in Eigensystem).
Eigensystem general_model_eigensystem(const SignedSvd& svd, const GeneralModelCoefficients& c);

// An invariant energy with Psi_IJ = 0, whose eigensystem is the closed form above.
class GeneralModelMaterial : public InvariantMaterial {
 public:
  struct Terms {
    double psi = 0.0;
    double dI = 0.0, dJ = 0.0;    // dPsi/dI_C, dPsi/dJ
    double dII = 0.0, dJJ = 0.0;  // second derivatives (no I_C-J coupling by construction)
  };
  virtual Terms terms(double Ic, double J) const = 0;
  // terms() without psi (0), where psi costs more than its derivatives.
  virtual Terms curvature_terms(double Ic, double J) const { return terms(Ic, J); }

  Derivatives invariant_derivatives(double Ic, double J) const final;
  Derivatives curvature_derivatives(double Ic, double J) const final { return derivatives(curvature_terms(Ic, J)); }
  static GeneralModelCoefficients coefficients(const Terms& t);  // Eq. 52
  // Inline: the batched element kernels call it per quadrature point.
  static Derivatives derivatives(const Terms& t) {
    Derivatives d;
    d.psi = t.psi;
    d.dI = t.dI;
    d.dJ = t.dJ;
    d.dII = t.dII;
    d.dIJ = 0.0;
    d.dJJ = t.dJJ;
    return d;
  }

 protected:
  Eigensystem eigensystem_impl(const Mat3& F) const override;
  // Psi and P straight from F (I_C, J, cofactor); the one SVD serves the projection only.
  Evaluation evaluate_impl(const Mat3& F, Projection mode) const override;
};

// lambda/2 (J - alpha)^2 written with shift = lambda (alpha - 1), which every model here knows
// exactly (mu, 3/4 mu, ...):  lambda/2 (J-1)^2 - shift (J-1) + shift^2 / (2 lambda).
// Expanding about J = 1 keeps the J-dependent part free of the large alpha when lambda is small.
struct ShiftedVolume {
  double lambda = 0.0;
  double shift = 0.0;
  double psi(double J) const;
  double dJ(double J) const { return lambda * (J - 1.0) - shift; }
  double dJJ() const { return lambda; }
};

}  // namespace sinew
