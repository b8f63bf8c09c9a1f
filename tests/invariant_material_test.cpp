// The InvariantMaterial base on its own: a test-local energy with every invariant
// derivative non-zero (including the cross term Psi_IJ), under the full derivative battery.
#include <gtest/gtest.h>

#include "material_test_support.hpp"

namespace sinew {
namespace {

// Psi = a (I - 3)^2 / 2 + b (J - 1)^2 / 2 + c (I - 3)(J - 1) + d (I - 3) - d... kept rest stable:
// P(I) = 2 Psi_I I + Psi_J I = 0 requires 2 Psi_I + Psi_J = 0 at (3, 1): use e (I - 3) - 2e (J - 1).
class CoupledInvariantEnergy final : public InvariantMaterial {
 public:
  std::string name() const override { return "coupled_invariant_test_energy"; }
  Derivatives invariant_derivatives(double I, double J) const override {
    const double x = I - 3.0, y = J - 1.0;
    Derivatives d;
    d.psi = 0.5 * a * x * x + 0.5 * b * y * y + c * x * y + e * x - 2.0 * e * y;
    d.dI = a * x + c * y + e;
    d.dJ = b * y + c * x - 2.0 * e;
    d.dII = a;
    d.dIJ = c;
    d.dJJ = b;
    return d;
  }
  double a = 0.3, b = 7.0, c = 0.4, e = 1.0;
};

TEST(InvariantMaterial, DerivativesEigensystemAndProjection) {
  const CoupledInvariantEnergy m;
  EXPECT_LE(m.pk1(Mat3::Identity()).norm(), 1e-14);
  const auto set = test::sample_set(99u, 10, true);
  ASSERT_GE(set.size(), 50u);
  for (const auto& s : set) {
    const Mat9 H = m.hessian(s.F);
    const double scale = std::max(1.0, H.norm());
    EXPECT_LE(test::rel_error(m.pk1(s.F), difference_pk1(m, s.F)), 1e-6) << test::describe(s);
    EXPECT_LE(test::rel_error(H, difference_hessian(m, s.F)), 1e-6) << test::describe(s);
    const Eigensystem es = m.eigensystem(s.F);
    EXPECT_LE((es.reconstruct() - H).norm() / scale, 1e-8) << test::describe(s);
    const Evaluation ev = m.evaluate(s.F, Projection::Clamp);
    EXPECT_LE((ev.hessian - test::numeric_projection(H, 0.0)).norm() / scale, 1e-9);
    EXPECT_LE(test::rel_error(ev.P, m.pk1(s.F)), 1e-12);
    // Stretch view agrees with the F view.
    const SignedSvd svd = signed_svd(s.F);
    EXPECT_NEAR(m.psi_stretch(svd.sigma), m.psi(s.F), 1e-10 * std::max(1.0, std::abs(m.psi(s.F))));
  }
}

}  // namespace
}  // namespace sinew
