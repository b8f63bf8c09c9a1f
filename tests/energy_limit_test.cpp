// Paper 001: corotational hexahedra, energy-limiting constraints and their Jacobians, PGS.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>

#include "sinew/core/finite_difference.hpp"
#include "sinew/forms/corotational_hex_form.hpp"
#include "sinew/constraints/energy_limit.hpp"
#include "sinew/forms/elastic_form.hpp"
#include "sinew/linalg/block_hessian.hpp"
#include "sinew/solver/pgs.hpp"
#include "sinew/material/families/neo_hookean.hpp"
#include "sinew/mesh/lattice.hpp"

namespace sinew {
namespace {

std::shared_ptr<const Discretization> one_hex(double sx = 0.3, double sy = 0.2, double sz = 0.25) {
  return std::make_shared<Discretization>(box_lattice(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(sx, sy, sz),
                                                      Eigen::Vector3i(1, 1, 1)));
}

CorotationalHexForm corotational(std::shared_ptr<const Discretization> d) {
  return CorotationalHexForm(std::move(d), HookeCoefficients::from_young_poisson(150e3, 0.3));
}

Eigen::VectorXd deformed(const Discretization& d, const Mat3& R, double noise, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-noise, noise);
  Eigen::VectorXd x = d.mesh().rest_positions();
  for (Eigen::Index v = 0; v < d.mesh().num_vertices(); ++v) {
    Vec3 p = x.segment<3>(3 * v);
    for (int i = 0; i < 3; ++i) p(i) += u(rng);
    x.segment<3>(3 * v) = R * p + Vec3(0.5, -0.2, 1.0);
  }
  return x;
}

// The corotational form's forces (minus its gradient: the warped elastic force) and its
// assembled Hessian (the warped stiffness), as the energy-limited stepper uses them.
Eigen::VectorXd forces(const Form& form, const Eigen::VectorXd& x) {
  Eigen::VectorXd g = Eigen::VectorXd::Zero(x.size());
  form.add_gradient(x, g);
  return -g;
}

Eigen::SparseMatrix<double> stiffness(const Form& form, const Eigen::VectorXd& x) {
  std::vector<std::vector<int>> cliques;
  form.couplings(cliques);
  BlockHessian H(x.size() / 3, cliques);
  form.add_hessian(x, H);
  return H.matrix();
}

Mat3 some_rotation(double angle = 0.9) { return Eigen::AngleAxisd(angle, Vec3(1, 2, -0.5).normalized()).toRotationMatrix(); }

// Central differences of a scalar function of x over every DOF (the library's core).
template <class Fn>
Eigen::VectorXd central_differences(const Fn& f, const Eigen::VectorXd& x, double step) {
  return difference_gradient(f, x, step);
}

TEST(HookeCoefficients, MatchPaperDefinitions) {
  const auto c = HookeCoefficients::from_young_poisson(2e6, 0.3);
  EXPECT_NEAR(c.E1, 2e6 * 0.7 / (1.3 * 0.4), 1e-6);
  EXPECT_NEAR(c.E2, 2e6 * 0.3 / (1.3 * 0.4), 1e-6);
  EXPECT_NEAR(c.E3, 2e6 / 2.6, 1e-6);
}

TEST(CorotationalHexForm, RigidRotationGivesThatRotationZeroEnergyAndForce) {
  auto d = one_hex();
  const CorotationalHexForm model = corotational(d);
  for (double angle : {0.3, 1.7, 3.0}) {
    const Mat3 R = some_rotation(angle);
    const Eigen::VectorXd x = deformed(*d, R, 0.0, 1);
    EXPECT_LE((model.rotation(0, x) - R).norm(), 1e-12) << angle;
    EXPECT_NEAR(model.element_value(0, x), 0.0, 1e-12);
    EXPECT_LE(forces(model, x).norm(), 1e-9);
    EXPECT_LE(model.element_gradient(0, x, JacobianKind::Exact).norm(), 1e-9);
  }
}

TEST(CorotationalHexForm, WarmStartedRotationsMatchTheSvdsPolarRotation) {
  // Whole-mesh passes start each element's polar decomposition from its rotation at the previous
  // positions (Newton on the rotation, falling back to the SVD). Along a path of small and large
  // increments, with an inverted element on the way, every rotation and the energy and exact
  // gradient built from it agree with a form that computes all of them afresh by the SVD.
  VolumeMesh mesh = box_lattice(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0.4, 0.3, 0.2), Eigen::Vector3i(2, 1, 1));
  auto d = std::make_shared<Discretization>(mesh);
  const CorotationalHexForm warm = corotational(d);
  const Eigen::VectorXd X = d->mesh().rest_positions();
  Eigen::VectorXd x_inverted = X;
  for (Eigen::Index v = 0; v < d->mesh().num_vertices(); ++v)
    if (X(3 * v) < 0.1) x_inverted(3 * v) = 0.3 - X(3 * v);  // element 0 turned inside out
  std::vector<Eigen::VectorXd> path;
  for (int k = 0; k <= 20; ++k) path.push_back(deformed(*d, some_rotation(0.02 * k), 0.01 + 0.002 * k, 7));
  path.push_back(deformed(*d, some_rotation(2.5), 0.05, 8));  // a jump: the warm start is far
  path.push_back(x_inverted);
  path.push_back(deformed(*d, some_rotation(2.4), 0.05, 9));
  for (std::size_t k = 0; k < path.size(); ++k) {
    const Eigen::VectorXd& x = path[k];
    std::vector<double> energies;
    warm.element_values(x, energies);  // a whole-mesh pass: warm-started from the previous x
    const CorotationalHexForm cold = corotational(d);
    for (Eigen::Index e = 0; e < d->num_elements(); ++e) {
      const Mat3 R = warm.rotation(e, x);
      EXPECT_LE((R - cold.rotation(e, x)).norm(), 1e-13) << "step " << k << " element " << e;
      EXPECT_LE((R.transpose() * R - Mat3::Identity()).norm(), 1e-14);
      EXPECT_NEAR(R.determinant(), 1.0, 1e-14);
      EXPECT_NEAR(energies[static_cast<size_t>(e)], cold.element_value(e, x), 1e-12 * (1.0 + std::abs(cold.element_value(e, x))));
      const Eigen::VectorXd g = warm.element_gradient(e, x, JacobianKind::Exact);
      EXPECT_LE((g - cold.element_gradient(e, x, JacobianKind::Exact)).norm(), 1e-10 * (1.0 + g.norm()))
          << "step " << k << " element " << e;
    }
  }
}

TEST(CorotationalHexForm, EnergyIsQuadraticFormOfStiffnessInUnrotatedFrame) {
  auto d = one_hex();
  const CorotationalHexForm model = corotational(d);
  const Eigen::VectorXd x = deformed(*d, some_rotation(), 0.03, 2);
  const Mat3 R = model.rotation(0, x);
  const Eigen::VectorXd X = d->mesh().rest_positions();
  Eigen::VectorXd u(24);
  for (int a = 0; a < 8; ++a) u.segment<3>(3 * a) = R.transpose() * x.segment<3>(3 * a) - X.segment<3>(3 * a);
  const double U = model.element_value(0, x);
  EXPECT_GT(U, 0.0);
  EXPECT_NEAR(U, 0.5 * u.dot(model.element_stiffness(0) * u), 1e-10 * U);
  // K_e annihilates the six rigid modes of the rest element.
  const Eigen::MatrixXd& K = model.element_stiffness(0);
  Eigen::VectorXd t(24), w(24);
  for (int a = 0; a < 8; ++a) {
    t.segment<3>(3 * a) = Vec3(1, 2, 3);
    w.segment<3>(3 * a) = Vec3(0.3, -0.1, 0.7).cross(Vec3(X.segment<3>(3 * a)));
  }
  EXPECT_LE((K * t).norm(), 1e-8 * K.norm());
  EXPECT_LE((K * w).norm(), 1e-8 * K.norm());
}

TEST(CorotationalHexForm, ExactGradientMatchesFiniteDifferencesOfEnergy) {
  // Several elements, sheared rest shape, large rotation plus deformation: the FD of U_e(x)
  // includes the change of the innermost tetrahedron's rotation.
  VolumeMesh mesh = box_lattice(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0.4, 0.3, 0.2), Eigen::Vector3i(2, 1, 1));
  for (Eigen::Index v = 0; v < mesh.num_vertices(); ++v) mesh.vertices(v, 0) += 0.2 * mesh.vertices(v, 2);
  auto d = std::make_shared<Discretization>(mesh);
  const CorotationalHexForm model = corotational(d);
  for (unsigned seed : {3u, 4u, 5u}) {
    const Eigen::VectorXd x = deformed(*d, some_rotation(0.4 * seed), 0.04, seed);
    for (Eigen::Index e = 0; e < d->num_elements(); ++e) {
      auto U = [&](const Eigen::VectorXd& y) { return model.element_value(e, y); };
      const Eigen::VectorXd fd = central_differences(U, x, 1e-6);
      const Eigen::VectorXd exact = model.element_gradient(e, x, JacobianKind::Exact);
      const Eigen::VectorXd warped = model.element_gradient(e, x, JacobianKind::Warped);
      Eigen::VectorXd fd_e(24);
      for (int a = 0; a < 8; ++a) fd_e.segment<3>(3 * a) = fd.segment<3>(3 * d->mesh().elements(e, a));
      EXPECT_LE((exact - fd_e).norm(), 1e-6 * fd_e.norm()) << "seed " << seed << " element " << e;
      // The warped force misses the rotation's change: visibly different at this deformation.
      EXPECT_GT((warped - fd_e).norm(), 1e-4 * fd_e.norm()) << "seed " << seed << " element " << e;
      // Both are tangent to rigid translations (forces sum to zero).
      EXPECT_LE(exact.reshaped(3, 8).rowwise().sum().norm(), 1e-9 * exact.norm());
    }
  }
}

TEST(CorotationalHexForm, StiffnessIsTheForceDerivativeAtRestAndAssemblesElementBlocks) {
  VolumeMesh mesh = box_lattice(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0.4, 0.3, 0.2), Eigen::Vector3i(2, 2, 1));
  auto d = std::make_shared<Discretization>(mesh);
  const CorotationalHexForm model = corotational(d);
  // At rest the rotation's change does not enter df/dx, so -K is the exact force Jacobian
  // there (and R K R^T of a rigidly rotated rest state is its rotated copy).
  const Eigen::VectorXd X = d->mesh().rest_positions();
  const Eigen::MatrixXd K(stiffness(model, X));
  const Eigen::MatrixXd fd = -difference_jacobian([&](const Eigen::VectorXd& y) { return forces(model, y); }, X, 1e-6);
  EXPECT_LE((K - fd).norm(), 1e-6 * K.norm());
  // Away from rest: the assembled matrix is the sum of the element blocks R K_e R^T.
  const Eigen::VectorXd x = deformed(*d, some_rotation(), 0.02, 13);
  Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(x.size(), x.size());
  for (Eigen::Index e = 0; e < d->num_elements(); ++e) {
    const Eigen::MatrixXd He = model.element_hessian(e, x);
    for (int a = 0; a < 8; ++a)
      for (int b = 0; b < 8; ++b)
        dense.block<3, 3>(3 * d->mesh().elements(e, a), 3 * d->mesh().elements(e, b)) += He.block<3, 3>(3 * a, 3 * b);
  }
  const Eigen::MatrixXd Kx(stiffness(model, x));
  EXPECT_LE((Kx - dense).norm(), 1e-12 * dense.norm());
  EXPECT_LE((Kx - Kx.transpose()).norm(), 1e-12 * dense.norm());
}

TEST(CorotationalHexForm, ElementHessianBlocksAreTheRotatedStiffnessBlocks) {
  // The pair kernel (all node pairs at once, the lower blocks mirrored) against R K_ab R^T
  // block by block with Eigen's products, on a rotated and deformed lattice.
  VolumeMesh mesh = box_lattice(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0.4, 0.3, 0.2), Eigen::Vector3i(2, 1, 1));
  auto d = std::make_shared<Discretization>(mesh);
  const CorotationalHexForm model = corotational(d);
  const Eigen::VectorXd x = deformed(*d, some_rotation(), 0.03, 5);
  for (Eigen::Index e = 0; e < d->num_elements(); ++e) {
    const Mat3 R = model.rotation(e, x);
    const Eigen::MatrixXd H = model.element_hessian(e, x);
    const auto& K = model.element_stiffness(e);
    for (int a = 0; a < 8; ++a)
      for (int b = 0; b < 8; ++b) {
        const Mat3 expected = R * K.block<3, 3>(3 * a, 3 * b) * R.transpose();
        EXPECT_LE((H.block<3, 3>(3 * a, 3 * b) - expected).norm(), 1e-14 * K.norm()) << "block " << a << ", " << b;
        // Below the diagonal, exactly the transposed block above it (as add_hessian assembles).
        if (a > b) {
          const Mat3 below = H.block<3, 3>(3 * a, 3 * b), mirrored = H.block<3, 3>(3 * b, 3 * a).transpose();
          EXPECT_TRUE(below == mirrored) << "block " << a << ", " << b;
        }
      }
  }
  // On one element the assembled Hessian is its block exactly (the same kernel values, diagonal
  // blocks as computed, not symmetrised).
  auto single = one_hex();
  const CorotationalHexForm one = corotational(single);
  const Eigen::VectorXd y = deformed(*single, some_rotation(0.4), 0.03, 7);
  const Eigen::MatrixXd assembled(stiffness(one, y));
  const Eigen::MatrixXd He = one.element_hessian(0, y);
  for (int a = 0; a < 8; ++a)
    for (int b = 0; b < 8; ++b) {
      const Mat3 from_element = He.block<3, 3>(3 * a, 3 * b);
      const Mat3 from_assembly =
          assembled.block<3, 3>(3 * single->mesh().elements(0, a), 3 * single->mesh().elements(0, b));
      EXPECT_TRUE(from_element == from_assembly) << "block " << a << ", " << b;
    }
}

TEST(EnergyLimit, ConstraintJacobianMatchesFiniteDifferencesOfC) {
  auto d = one_hex();
  const CorotationalHexForm model = corotational(d);
  const EnergyLimit limit{0.05, JacobianKind::Exact};
  const Eigen::VectorXd x = deformed(*d, some_rotation(2.0), 0.03, 7);
  auto C = [&](const Eigen::VectorXd& y) { return energy_constraint(model, 0, y, limit.max_energy); };
  EXPECT_NEAR(C(x), 1.0 - model.element_value(0, x) / 0.05, 1e-14);
  const Eigen::VectorXd fd = central_differences(C, x, 1e-6);
  const Eigen::VectorXd J = energy_constraint_jacobian(model, 0, x, limit);
  EXPECT_LE((J - fd).norm(), 1e-6 * fd.norm());
}

TEST(EnergyLimit, HyperelasticElementGradientMatchesFiniteDifferences) {
  auto d = std::make_shared<Discretization>(
      box_lattice(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0.3, 0.2, 0.2), Eigen::Vector3i(2, 1, 1)));
  const ElasticForm model(d, std::make_shared<NeoHookean>(40e3, 20e3));
  EXPECT_FALSE(model.supports(JacobianKind::Warped));
  const Eigen::VectorXd x = deformed(*d, some_rotation(), 0.02, 9);
  for (Eigen::Index e = 0; e < d->num_elements(); ++e) {
    const EnergyLimit limit{0.5, JacobianKind::Exact};
    auto C = [&](const Eigen::VectorXd& y) { return energy_constraint(model, e, y, limit.max_energy); };
    const Eigen::VectorXd fd = central_differences(C, x, 1e-7);
    const Eigen::VectorXd J = energy_constraint_jacobian(model, e, x, limit);
    Eigen::VectorXd fd_e(24);
    for (int a = 0; a < 8; ++a) fd_e.segment<3>(3 * a) = fd.segment<3>(3 * d->mesh().elements(e, a));
    EXPECT_LE((J - fd_e).norm(), 1e-6 * fd_e.norm());
  }
  // The element energies sum to the form's total, and forces are minus its gradient.
  double total = 0.0;
  for (Eigen::Index e = 0; e < d->num_elements(); ++e) total += model.element_value(e, x);
  const ElasticForm form(d, std::make_shared<NeoHookean>(40e3, 20e3));
  EXPECT_NEAR(total, form.value(x), 1e-10 * total);
}

TEST(Pgs, SolvesTwoByTwoLcpWithKnownSolution) {
  Eigen::MatrixXd W(2, 2);
  W << 2, 1, 1, 2;
  const Eigen::VectorXd q = Eigen::Vector2d(-1, 1);
  Eigen::VectorXd lambda;
  const PgsReport r = solve_pgs(W, q, {LcpRow{}, LcpRow{}}, lambda, {});
  EXPECT_TRUE(r.converged);
  EXPECT_NEAR(lambda(0), 0.5, 1e-8);
  EXPECT_NEAR(lambda(1), 0.0, 1e-12);
}

TEST(Pgs, MatchesEnumeratedActiveSetOnRandomLcps) {
  // Unilateral LCPs with SPD W have a unique solution; find it by trying all 2^m active sets.
  std::mt19937 rng(11);
  std::normal_distribution<double> g(0.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    const int m = 5;
    Eigen::MatrixXd B(m, m);
    for (int i = 0; i < m; ++i)
      for (int j = 0; j < m; ++j) B(i, j) = g(rng);
    const Eigen::MatrixXd W = B * B.transpose() + 0.5 * Eigen::MatrixXd::Identity(m, m);
    Eigen::VectorXd q(m);
    for (int i = 0; i < m; ++i) q(i) = g(rng);
    Eigen::VectorXd expected;
    for (int mask = 0; mask < (1 << m); ++mask) {
      std::vector<int> act;
      for (int i = 0; i < m; ++i)
        if (mask & (1 << i)) act.push_back(i);
      Eigen::VectorXd lam = Eigen::VectorXd::Zero(m);
      if (!act.empty()) {
        Eigen::MatrixXd Wa(act.size(), act.size());
        Eigen::VectorXd qa(act.size());
        for (size_t i = 0; i < act.size(); ++i) {
          qa(i) = -q(act[i]);
          for (size_t j = 0; j < act.size(); ++j) Wa(i, j) = W(act[i], act[j]);
        }
        const Eigen::VectorXd la = Wa.ldlt().solve(qa);
        for (size_t i = 0; i < act.size(); ++i) lam(act[i]) = la(i);
      }
      const Eigen::VectorXd w = W * lam + q;
      if (lam.minCoeff() >= -1e-12 && w.minCoeff() >= -1e-10) {
        expected = lam;
        break;
      }
    }
    ASSERT_EQ(expected.size(), m);
    Eigen::VectorXd lambda;
    const PgsReport r = solve_pgs(W, q, std::vector<LcpRow>(m), lambda, {5000, 1e-11});
    EXPECT_TRUE(r.converged) << trial;
    EXPECT_LE((lambda - expected).norm(), 1e-7 * (1 + expected.norm())) << trial;
  }
}

TEST(Pgs, FrictionBoxLimitsTangentialImpulse) {
  // One contact, W = I: the normal impulse stops the approach (lambda_n = 1); sliding at 2 m/s
  // needs more than mu lambda_n, so the tangent impulse saturates at -mu lambda_n and the
  // second direction, already at rest, gets none.
  const Eigen::MatrixXd W = Eigen::MatrixXd::Identity(3, 3);
  const Eigen::VectorXd q = Eigen::Vector3d(-1, 2, 0);
  const std::vector<LcpRow> rows = {LcpRow{}, LcpRow{0, 0.5}, LcpRow{0, 0.5}};
  Eigen::VectorXd lambda;
  const PgsReport r = solve_pgs(W, q, rows, lambda, {});
  EXPECT_TRUE(r.converged);
  EXPECT_NEAR(lambda(0), 1.0, 1e-12);
  EXPECT_NEAR(lambda(1), -0.5, 1e-12);
  EXPECT_NEAR(lambda(2), 0.0, 1e-12);
  // Slow sliding (0.2 m/s) sticks: the tangent impulse cancels it inside the cone.
  Eigen::VectorXd lambda2;
  solve_pgs(W, Eigen::Vector3d(-1, 0.2, 0), rows, lambda2, {});
  EXPECT_NEAR(lambda2(1), -0.2, 1e-12);
  EXPECT_LE(lcp_residual(W, Eigen::Vector3d(-1, 0.2, 0), rows, lambda2), 1e-12);
}

}  // namespace
}  // namespace sinew
