// The closed-form eigensystems of both stable Neo-Hookean variants (paper 000 §4.5-4.6,
// Appendix A and D) against a numeric 9x9 eigendecomposition of a Hessian assembled here from
// Eq. 41 / Eq. 65, and against the paper's own formulas: the six pair eigenvalues
// mu_T +- lambda (J - alpha) sigma_k with eigenvectors U D_k V^T / sqrt(2) (Appendix A), the
// cubic (Eq. 42-43, Eq. 66) and the scaling-mode eigenvectors (Eq. 44, Eq. 67).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "material_test_support.hpp"
#include "sinew/core/svd.hpp"
#include "sinew/material/families.hpp"

namespace sinew {
namespace {

struct Case {
  Mat3 F;
  std::string what;
};

// The two variants in the paper's notation: A = mu_T I + gamma_F f f^T + lambda g g^T
// + lambda (J - alpha) H, with gamma_F = 2 mu/(I_C + 1)^2 for Eq. 14 and 0 for Eq. 13.
struct Variant {
  std::string name;
  double lambda, mu;
  bool barrier;  // Eq. 14 (true) or Eq. 13 (false)
  double alpha() const { return barrier ? 1.0 + mu / lambda - mu / (4.0 * lambda) : 1.0 + mu / lambda; }
  double mu_T(double Ic) const { return barrier ? mu * (1.0 - 1.0 / (Ic + 1.0)) : mu; }
  double gamma_F(double Ic) const { return barrier ? 2.0 * mu / ((Ic + 1.0) * (Ic + 1.0)) : 0.0; }
  std::unique_ptr<Material> make() const {
    if (barrier) return std::make_unique<StableNeoHookean>(lambda, mu);
    return std::make_unique<StableNeoHookeanEq13>(lambda, mu);
  }
};

// d^2 J / dF^2 without the library: J is affine in every single entry of F, so the mixed second
// difference with unit steps is exact, and the diagonal is zero.
Mat9 volume_hessian_reference(const Mat3& F) {
  Mat9 H = Mat9::Zero();
  for (int a = 0; a < 9; ++a)
    for (int b = 0; b < 9; ++b) {
      if (a == b) continue;
      Mat3 Fa = F, Fb = F, Fab = F;
      Fa(a % 3, a / 3) += 1.0;
      Fb(b % 3, b / 3) += 1.0;
      Fab(a % 3, a / 3) += 1.0;
      Fab(b % 3, b / 3) += 1.0;
      H(a, b) = Fab.determinant() - Fa.determinant() - Fb.determinant() + F.determinant();
    }
  return H;
}

// Eq. 41 (Eq. 65 without the barrier), assembled term by term.
Mat9 hessian_reference(const Variant& m, const Mat3& F) {
  const double Ic = F.squaredNorm(), J = F.determinant();
  const Vec9 f = vec(F);
  const Vec9 g = vec(cofactor(F));
  return m.mu_T(Ic) * Mat9::Identity() + m.gamma_F(Ic) * f * f.transpose() +
         m.lambda * g * g.transpose() + m.lambda * (J - m.alpha()) * volume_hessian_reference(F);
}

std::vector<Case> cases(const Variant& m, unsigned seed) {
  std::vector<Case> out;
  for (const auto& s : test::sample_set(seed, 10, true)) out.push_back({s.F, test::describe(s)});
  std::mt19937 rng(seed + 1);
  std::uniform_real_distribution<double> u(0.5, 2.0);
  for (int i = 0; i < 5; ++i) {  // F near 0 (meta-stability, §3.3)
    const Vec3 s(1e-4 * u(rng), 1e-4 * u(rng), -1e-4 * u(rng));
    out.push_back({test::random_rotation(rng) * s.asDiagonal() * test::random_rotation(rng),
                   "near zero"});
  }
  out.push_back({Mat3::Zero(), "F = 0"});
  for (int i = 0; i < 5; ++i) {  // J = alpha: gamma_H = 0, the cubic degenerates
    const double a = u(rng), b = u(rng);
    const Vec3 s(a, b, m.alpha() / (a * b));
    out.push_back({test::random_rotation(rng) * s.asDiagonal() * test::random_rotation(rng),
                   "J = alpha"});
  }
  for (int i = 0; i < 3; ++i) {  // exact ties sigma_i = sigma_j, also inverted
    const double a = u(rng);
    const Vec3 s = i == 0 ? Vec3(a, a, u(rng)) : i == 1 ? Vec3(a, a, a) : Vec3(u(rng), a, -a);
    out.push_back({test::random_rotation(rng) * s.asDiagonal() * test::random_rotation(rng),
                   "tie " + std::to_string(i)});
  }
  for (int i = 0; i < 6; ++i) {  // near rest: the scaling block's eigenvalues cluster there
    const double size = std::pow(10.0, -2.0 - i);
    const Vec3 s = Vec3::Ones() + size * Vec3(u(rng) - 1.25, u(rng) - 1.25, u(rng) - 1.25);
    out.push_back({test::random_rotation(rng) * s.asDiagonal() * test::random_rotation(rng),
                   "near rest " + std::to_string(size)});
  }
  out.push_back({Vec3(5.0, 5.0, 0.2).asDiagonal(), "stretch 5, flat"});
  out.push_back({Vec3(5.0, 4.0, 3.0).asDiagonal(), "stretch 5"});
  out.push_back({-Mat3::Identity(), "F = -I"});
  return out;
}

// Default-like, soft, nearly incompressible, and lambda_Lame = 0 (nu = 0), where the whole
// scaling block is a multiple of the identity at rest: a triple eigenvalue that clusters nearby.
const Variant kVariants[] = {
    {"Eq. 14", 10.0, 1.0, true},         {"Eq. 14 soft", 0.7, 2.0, true},
    {"Eq. 14 stiff", 500.0, 1.0, true},  {"Eq. 14 nu=0", 0.625, 1.0, true},
    {"Eq. 13", 10.0, 1.0, false},        {"Eq. 13 soft", 0.7, 2.0, false},
    {"Eq. 13 stiff", 500.0, 1.0, false}, {"Eq. 13 nu=0", 1.0, 1.0, false}};
constexpr int kVariantCount = 8;

// Appendix A, as printed (signs included; only the span of each matters).
Mat3 appendix_a(int k) {
  Mat3 D = Mat3::Zero();
  switch (k) {
    case 3: D(1, 2) = 1; D(2, 1) = -1; break;
    case 4: D(0, 2) = 1; D(2, 0) = -1; break;
    case 5: D(0, 1) = 1; D(1, 0) = -1; break;
    case 6: D(1, 2) = 1; D(2, 1) = 1; break;
    case 7: D(0, 2) = 1; D(2, 0) = 1; break;
    case 8: D(0, 1) = 1; D(1, 0) = 1; break;
  }
  return D;
}

TEST(SnhEigensystem, ClosedFormMatchesNumericDecomposition) {
  int checked = 0;
  double worst_value = 0.0, worst_residual = 0.0;
  for (const Variant& m : kVariants) {
    const auto material = m.make();
    for (const Case& c : cases(m, 42u)) {
      const Mat9 H = hessian_reference(m, c.F);
      const double scale = std::max(1.0, H.norm());
      // The library's own Hessian is Eq. 41 too.
      EXPECT_LE((material->hessian(c.F) - H).norm() / scale, 1e-13) << m.name << " " << c.what;
      const Eigensystem es = material->eigensystem(c.F);
      Vec9 values = es.values;
      std::sort(values.data(), values.data() + 9);
      const double value_error = (values - test::numeric_eigenvalues(H)).norm() / scale;
      EXPECT_LE(value_error, 1e-11) << m.name << " " << c.what;
      EXPECT_LE((es.vectors.transpose() * es.vectors - Mat9::Identity()).norm(), 1e-12)
          << m.name << " " << c.what;
      for (int k = 0; k < 9; ++k) {
        const double r = (H * es.vectors.col(k) - es.values(k) * es.vectors.col(k)).norm() / scale;
        worst_residual = std::max(worst_residual, r);
        EXPECT_LE(r, 1e-11) << m.name << " " << c.what << " eigenpair " << k;
      }
      worst_value = std::max(worst_value, value_error);
      ++checked;
    }
  }
  EXPECT_GE(checked, kVariantCount * 50);
  std::printf("closed form vs numeric over %d F: worst eigenvalue error %.2e, worst residual %.2e "
              "(relative to ||H||)\n",
              checked, worst_value, worst_residual);
}

TEST(SnhEigensystem, SixPairModesAreThePapersClosedForm) {
  for (const Variant& m : kVariants) {
    const auto material = m.make();
    for (const Case& c : cases(m, 7u)) {
      const Mat9 H = hessian_reference(m, c.F);
      const double scale = std::max(1.0, H.norm());
      const SignedSvd svd = signed_svd(c.F);
      const double Ic = c.F.squaredNorm(), J = c.F.determinant();
      const double gH = m.lambda * (J - m.alpha());
      const Eigensystem es = material->eigensystem(c.F);
      for (int k = 3; k < 9; ++k) {
        const int axis = (k - 3) % 3;
        const double sign = k < 6 ? 1.0 : -1.0;
        const double expected = m.mu_T(Ic) + sign * gH * svd.sigma(axis);  // Eq. 46-48
        EXPECT_NEAR(es.values(k), expected, 1e-12 * scale) << m.name << " " << c.what << " " << k;
        const Vec9 q = vec(svd.U * appendix_a(k) * svd.V.transpose()) / std::sqrt(2.0);  // Eq. 62
        EXPECT_LE((H * q - expected * q).norm() / scale, 1e-12) << m.name << " " << c.what << " " << k;
        EXPECT_NEAR(std::abs(q.dot(es.vectors.col(k))), 1.0, 1e-12) << m.name << " " << c.what << " " << k;
      }
    }
  }
}

// Eq. 42 with Eq. 43 (de-garbled; eta = gamma_F / (lambda (J - alpha)), rho = 1/(J - alpha)),
// which for gamma_F = 0 is Appendix D's Eq. 66.
double papers_cubic(const Variant& m, const Vec3& s, double eps_bar, double& magnitude) {
  const double Ic = s.squaredNorm(), J = s.prod();
  const double g2 = Vec3(s(1) * s(2), s(0) * s(2), s(0) * s(1)).squaredNorm();
  const double rho = 1.0 / (J - m.alpha());
  double c2, c1, c0;
  if (m.barrier) {
    const double eta = m.gamma_F(Ic) / (m.lambda * (J - m.alpha()));
    c2 = -(g2 * rho + Ic * eta);
    c1 = -(1.0 + 2.0 * J * rho) * Ic - 6.0 * J * eta + (g2 * Ic - 9.0 * J * J) * rho * eta;
    c0 = -(2.0 + 3.0 * J * rho) * J + (Ic * Ic - 4.0 * g2) * eta +
         2.0 * J * (Ic * Ic - 3.0 * g2) * rho * eta;
  } else {  // Eq. 66
    c2 = -rho * g2;
    c1 = -(1.0 + 2.0 * rho * J) * Ic;
    c0 = -(2.0 + 3.0 * rho * J) * J;
  }
  const double e = eps_bar;
  magnitude = std::abs(e * e * e) + std::abs(c2 * e * e) + std::abs(c1 * e) + std::abs(c0);
  return e * e * e + c2 * e * e + c1 * e + c0;
}

// Eq. 44 (Eq. 67 for the variant without barrier): the scaling-mode eigenvector's diagonal.
Vec3 papers_scaling_diagonal(const Variant& m, const Vec3& s, double e) {
  const double Ic = s.squaredNorm(), J = s.prod();
  const double rho = 1.0 / (J - m.alpha());
  const double s0 = s(0), s1 = s(1), s2 = s(2);
  if (!m.barrier) {  // Eq. 67
    const double a = 1.0 + rho * J;
    const double b = a + rho * (J + (s0 * s0 + s1 * s1) * e);
    return {a * (s0 * s2 + s1 * e), a * (s1 * s2 + s0 * e), e * e - b * s2 * s2};
  }
  const double eta = m.gamma_F(Ic) / (m.lambda * (J - m.alpha()));
  const double q0 = s0 * s0, q1 = s1 * s1, q2 = s2 * s2;
  return {e * (s1 + s0 * s2 * eta + J * s1 * rho) + s0 * s2 + s1 * (q0 - q1 + q2) * eta +
              J * s0 * s2 * rho + s0 * (q0 - q1) * s2 * (q1 - q2) * rho * eta,
          e * (s0 + s1 * s2 * eta + J * s0 * rho) + s1 * s2 - s0 * (q0 - q1 - q2) * eta +
              J * s1 * s2 * rho - s1 * (q0 - q1) * s2 * (q0 - q2) * rho * eta,
          e * e - e * (q0 + q1) * (eta + q2 * rho) - q2 - 2.0 * J * eta - 2.0 * J * q2 * rho +
              (q0 - q1) * (q0 - q1) * q2 * rho * eta};
}

TEST(SnhEigensystem, ScalingModesSolveThePapersCubicAndEigenvectors) {
  int cubic_checks = 0, vector_checks = 0;
  for (const Variant& m : kVariants) {
    const auto material = m.make();
    for (const Case& c : cases(m, 11u)) {
      const SignedSvd svd = signed_svd(c.F);
      const double Ic = c.F.squaredNorm(), J = c.F.determinant();
      const double gH = m.lambda * (J - m.alpha());
      if (std::abs(J - m.alpha()) < 1e-6) continue;  // eps_bar undefined at J = alpha
      const Mat9 H = hessian_reference(m, c.F);
      const double scale = std::max(1.0, H.norm());
      const Eigensystem es = material->eigensystem(c.F);
      for (int k = 0; k < 3; ++k) {
        const double eps_bar = (es.values(k) - m.mu_T(Ic)) / gH;  // Eq. 45
        double magnitude = 0.0;
        const double residual = papers_cubic(m, svd.sigma, eps_bar, magnitude);
        EXPECT_LE(std::abs(residual), 1e-9 * magnitude) << m.name << " " << c.what << " root " << k;
        ++cubic_checks;

        // Eq. 44 / 67 gives the eigenvector only where it does not vanish and the eigenvalue is
        // simple (it is a polynomial formula: at ties it can collapse to zero).
        double gap = 1e300;
        for (int j = 0; j < 9; ++j) {
          if (j != k) gap = std::min(gap, std::abs(es.values(j) - es.values(k)));
        }
        const Vec3 d = papers_scaling_diagonal(m, svd.sigma, eps_bar);
        const double size = d.norm() / (1.0 + eps_bar * eps_bar + Ic * Ic);
        if (gap < 1e-3 * scale || size < 1e-3) continue;
        const Vec9 q = vec(svd.U * d.asDiagonal() * svd.V.transpose()).normalized();  // Eq. 39
        EXPECT_LE((H * q - es.values(k) * q).norm() / scale, 1e-8) << m.name << " " << c.what;
        EXPECT_NEAR(std::abs(q.dot(es.vectors.col(k))), 1.0, 1e-8) << m.name << " " << c.what;
        ++vector_checks;
      }
    }
  }
  std::printf("cubic checked at %d roots, Eq. 44/67 eigenvectors at %d\n", cubic_checks,
              vector_checks);
  EXPECT_GE(cubic_checks, kVariantCount * 3 * 50);
  EXPECT_GE(vector_checks, kVariantCount * 50);
}

// The library's scaled cubic (no division by gamma_H) is the paper's Eq. 42 times gamma_H^3.
TEST(SnhEigensystem, ScaledCubicIsThePapersCubic) {
  std::mt19937 rng(3);
  for (int i = 0; i < 50; ++i) {
    const Vec3 s = test::random_F(rng, test::FKind::LargeStretch).sigma;
    const Variant m = kVariants[i % kVariantCount];
    const double Ic = s.squaredNorm(), J = s.prod();
    const GeneralModelCoefficients c{m.mu_T(Ic), m.gamma_F(Ic), m.lambda, m.lambda * (J - m.alpha())};
    const Vec3 a = general_model_cubic(s, c);
    const double gH = c.gamma_H;
    for (double x : {-2.0, 0.3, 1.7}) {
      double magnitude = 0.0;
      const double paper = papers_cubic(m, s, x, magnitude);
      const double ours = std::pow(gH * x, 3) + a(2) * std::pow(gH * x, 2) + a(1) * gH * x + a(0);
      EXPECT_NEAR(ours, std::pow(gH, 3) * paper, 1e-10 * std::pow(std::abs(gH), 3) * magnitude);
    }
  }
}

TEST(SnhEigensystem, NoDivisionByZeroAnywhere) {
  for (const Variant& m : kVariants) {
    const auto material = m.make();
    for (const Mat3& F : {Mat3(Mat3::Zero()), Mat3(Vec3(m.alpha(), 1.0, 1.0).asDiagonal()),
                          Mat3(Vec3(2.0, 2.0, 2.0).asDiagonal()), Mat3(-Mat3::Identity()),
                          Mat3(Vec3(1.0, 0.0, 0.0).asDiagonal())}) {
      const Eigensystem es = material->eigensystem(F);
      EXPECT_TRUE(es.values.allFinite() && es.vectors.allFinite()) << m.name << "\n" << F;
      const Evaluation e = material->evaluate(F);
      EXPECT_TRUE(std::isfinite(e.psi) && e.P.allFinite() && e.hessian.allFinite());
    }
  }
}

}  // namespace
}  // namespace sinew
