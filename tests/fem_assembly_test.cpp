// Whole-mesh derivatives and consistency of the hex and tet discretisations.
#include <gtest/gtest.h>

#include <random>
#include <set>

#include "sinew/assembly/problem.hpp"
#include "sinew/element/discretization.hpp"
#include "sinew/element/element_rule.hpp"
#include "sinew/forms/elastic_form.hpp"
#include "sinew/material/families/corotational.hpp"
#include "sinew/mesh/lattice.hpp"
#include "sinew/solver/newton.hpp"

namespace sinew {
namespace {

VolumeMesh small_mesh(ElementKind kind) {
  // A slightly sheared box so that element Jacobians are not all identical.
  VolumeMesh m = box_lattice(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1.0, 0.8, 1.2), Eigen::Vector3i(2, 2, 2));
  for (Eigen::Index v = 0; v < m.num_vertices(); ++v) m.vertices(v, 0) += 0.1 * m.vertices(v, 2);
  return kind == ElementKind::Hex8 ? m : tetrahedralize_hexes(m);
}

std::shared_ptr<const Material> test_material() {
  return std::make_shared<LinearCorotational>(5.0, 1.0);
}

class MeshDerivatives : public ::testing::TestWithParam<ElementKind> {};

TEST_P(MeshDerivatives, AffineMotionGivesExactDeformationGradient) {
  const Discretization d(small_mesh(GetParam()));
  Mat3 A;
  A << 1.2, 0.1, -0.3, 0.05, 0.9, 0.2, 0.0, -0.1, 1.1;
  Eigen::VectorXd x = d.mesh().rest_positions();
  for (Eigen::Index v = 0; v < d.mesh().num_vertices(); ++v)
    x.segment<3>(3 * v) = A * x.segment<3>(3 * v) + Eigen::Vector3d(0.3, -0.2, 0.1);
  double volume = 0.0;
  for (Eigen::Index e = 0; e < d.num_elements(); ++e) {
    volume += d.rest_volume(e);
    for (int q = 0; q < d.quadrature_points(); ++q)
      EXPECT_LE((d.deformation_gradient(e, q, x) - A).norm(), 1e-12);
  }
  EXPECT_NEAR(volume, 1.0 * 0.8 * 1.2, 1e-12);
}

TEST_P(MeshDerivatives, GradientAndHessianMatchFiniteDifferences) {
  auto disc = std::make_shared<Discretization>(small_mesh(GetParam()));
  const ElasticForm form(disc, test_material(), Projection::None);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.15, 0.15);
  Eigen::VectorXd x = disc->mesh().rest_positions();
  for (Eigen::Index i = 0; i < x.size(); ++i) x(i) += u(rng);

  Eigen::VectorXd g = Eigen::VectorXd::Zero(x.size());
  form.add_gradient(x, g);
  std::vector<std::vector<int>> cliques;
  form.couplings(cliques);
  BlockHessian H(disc->mesh().num_vertices(), cliques);
  form.add_hessian(x, H);
  const Eigen::MatrixXd K(H.matrix());

  const double h = 1e-5;
  Eigen::VectorXd g_fd(x.size());
  Eigen::MatrixXd K_fd(x.size(), x.size());
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    Eigen::VectorXd xp = x, xm = x;
    xp(i) += h;
    xm(i) -= h;
    g_fd(i) = (form.value(xp) - form.value(xm)) / (2 * h);
    Eigen::VectorXd gp = Eigen::VectorXd::Zero(x.size()), gm = gp;
    form.add_gradient(xp, gp);
    form.add_gradient(xm, gm);
    K_fd.col(i) = (gp - gm) / (2 * h);
  }
  EXPECT_LE((g - g_fd).norm() / g.norm(), 1e-7);
  EXPECT_LE((K - K_fd).norm() / K.norm(), 1e-7);
  EXPECT_LE((K - K.transpose()).norm(), 1e-10 * K.norm());
}

TEST_P(MeshDerivatives, ColourGroupsShareNoVertex) {
  const Discretization d(small_mesh(GetParam()));
  Eigen::Index total = 0;
  for (const auto& group : d.color_groups()) {
    std::set<int> seen;
    for (Eigen::Index e : group)
      for (int a = 0; a < d.nodes(); ++a) EXPECT_TRUE(seen.insert(d.mesh().elements(e, a)).second);
    total += static_cast<Eigen::Index>(group.size());
  }
  EXPECT_EQ(total, d.num_elements());
}

TEST_P(MeshDerivatives, PatchTestReproducesAffineField) {
  // Boundary vertices follow an affine map; Newton must put every interior vertex on it.
  VolumeMesh mesh = box_lattice(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1), Eigen::Vector3i(3, 3, 3));
  if (GetParam() == ElementKind::Tet4) mesh = tetrahedralize_hexes(mesh);
  // Perturb interior rest positions so the patch is irregular.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-0.08, 0.08);
  auto on_boundary = [](const Eigen::Vector3d& p) {
    return (p.array() < 1e-12).any() || (p.array() > 1 - 1e-12).any();
  };
  for (Eigen::Index v = 0; v < mesh.num_vertices(); ++v)
    if (!on_boundary(mesh.vertices.row(v).transpose()))
      for (int i = 0; i < 3; ++i) mesh.vertices(v, i) += u(rng);
  auto disc = std::make_shared<Discretization>(mesh);
  Problem problem(mesh.num_vertices());
  problem.add_form(std::make_shared<ElasticForm>(disc, test_material()));
  Mat3 A;
  A << 1.1, 0.2, 0.0, -0.1, 0.95, 0.1, 0.05, 0.0, 1.05;
  const Eigen::Vector3d t(0.1, 0.2, -0.3);
  std::vector<char> fixed(3 * mesh.num_vertices(), 0);
  Eigen::VectorXd x = mesh.rest_positions();
  for (Eigen::Index v = 0; v < mesh.num_vertices(); ++v)
    if (on_boundary(mesh.vertices.row(v).transpose())) {
      x.segment<3>(3 * v) = A * mesh.vertices.row(v).transpose() + t;
      fixed[3 * v] = fixed[3 * v + 1] = fixed[3 * v + 2] = 1;
    }
  problem.set_fixed(fixed);
  auto linear = make_linear_solver({});
  NewtonSettings settings;
  settings.test = ConvergenceTest::Absolute;
  settings.absolute_tolerance = 1e-11;
  const NewtonReport r = newton_solve(problem, x, *linear, settings);
  ASSERT_TRUE(r.converged) << r.failure;
  for (Eigen::Index v = 0; v < mesh.num_vertices(); ++v)
    EXPECT_LE((x.segment<3>(3 * v) - (A * mesh.vertices.row(v).transpose() + t)).norm(), 1e-10);
}

TEST_P(MeshDerivatives, EqualRestShapesShareGradients) {
  // A regular lattice has one hexahedron shape (and a few tetrahedron shapes); moving one
  // vertex gives its elements shapes of their own. Every element's gradients and weights must
  // be its own, computed from scratch.
  VolumeMesh mesh = box_lattice(Eigen::Vector3d(0.3, -0.2, 0.1), Eigen::Vector3d(1.3, 0.8, 1.6), Eigen::Vector3i(3, 3, 3));
  if (GetParam() == ElementKind::Tet4) mesh = tetrahedralize_hexes(mesh);
  const Discretization regular(mesh);
  EXPECT_LE(regular.num_rest_shapes(), GetParam() == ElementKind::Hex8 ? 1 : 12);
  mesh.vertices(21, 1) += 0.05;  // an interior vertex
  const Discretization moved(mesh);
  EXPECT_GT(moved.num_rest_shapes(), regular.num_rest_shapes());
  EXPECT_LT(moved.num_rest_shapes(), moved.num_elements());
  const QuadratureRule& rule = quadrature_rule(mesh.kind);
  for (Eigen::Index e = 0; e < moved.num_elements(); ++e) {
    Eigen::MatrixX3d X(moved.nodes(), 3);
    for (int a = 0; a < moved.nodes(); ++a) X.row(a) = mesh.vertices.row(mesh.elements(e, a));
    for (int q = 0; q < moved.quadrature_points(); ++q) {
      const Mat3 J = X.transpose() * rule.dN_dxi[static_cast<size_t>(q)];
      EXPECT_LE((moved.gradients(e, q) - rule.dN_dxi[static_cast<size_t>(q)] * J.inverse()).norm(), 1e-12);
      EXPECT_NEAR(moved.weight(e, q), rule.weights[static_cast<size_t>(q)] * J.determinant(), 1e-14);
    }
  }
}

TEST_P(MeshDerivatives, AssembledHessianIsTheSumOfElementHessians) {
  // The assembly loop (fixed-size kernels, scatter map, upper blocks mirrored) against the
  // per-element interface, with the projection on, at a deformed state with inverted elements.
  auto disc = std::make_shared<Discretization>(small_mesh(GetParam()));
  const ElasticForm form(disc, test_material(), Projection::Clamp);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-0.4, 0.4);
  Eigen::VectorXd x = disc->mesh().rest_positions();
  for (Eigen::Index i = 0; i < x.size(); ++i) x(i) += u(rng);
  std::vector<std::vector<int>> cliques;
  form.couplings(cliques);
  BlockHessian H(disc->mesh().num_vertices(), cliques);
  form.add_hessian(x, H);
  form.add_hessian(x, H);  // a second pass reuses the scatter map
  const Eigen::MatrixXd K(H.matrix());
  Eigen::MatrixXd reference = Eigen::MatrixXd::Zero(x.size(), x.size());
  const auto& elements = disc->mesh().elements;
  for (Eigen::Index e = 0; e < disc->num_elements(); ++e) {
    const Eigen::MatrixXd Ke = form.element_hessian(e, x);
    for (int a = 0; a < disc->nodes(); ++a)
      for (int b = 0; b < disc->nodes(); ++b)
        reference.block<3, 3>(3 * elements(e, a), 3 * elements(e, b)) += 2.0 * Ke.block<3, 3>(3 * a, 3 * b);
  }
  EXPECT_LE((K - reference).norm(), 1e-12 * reference.norm());
  EXPECT_EQ((K - K.transpose()).norm(), 0.0);  // upper blocks mirrored: exactly symmetric
}

TEST_P(MeshDerivatives, FixedDofsGetIdentityRowsAndColumns) {
  auto disc = std::make_shared<Discretization>(small_mesh(GetParam()));
  auto form = std::make_shared<ElasticForm>(disc, test_material());
  Problem problem(disc->mesh().num_vertices());
  problem.add_form(form);
  std::vector<char> fixed(static_cast<size_t>(problem.num_dofs()), 0);
  for (size_t i = 0; i < fixed.size(); i += 7) fixed[i] = 1;  // single components of some vertices
  fixed[3] = fixed[4] = fixed[5] = 1;                          // all of one vertex
  problem.set_fixed(fixed);
  Eigen::VectorXd x = disc->mesh().rest_positions() * 1.1;
  const Eigen::MatrixXd K(*problem.hessian(x).matrix());
  std::vector<std::vector<int>> cliques;
  form->couplings(cliques);
  BlockHessian H(disc->mesh().num_vertices(), cliques);
  form->add_hessian(x, H);
  Eigen::MatrixXd expected(H.matrix());
  for (Eigen::Index i = 0; i < expected.rows(); ++i)
    if (fixed[static_cast<size_t>(i)]) {
      expected.row(i).setZero();
      expected.col(i).setZero();
      expected(i, i) = 1.0;
    }
  EXPECT_EQ((K - expected).norm(), 0.0);
}

INSTANTIATE_TEST_SUITE_P(Kinds, MeshDerivatives, ::testing::Values(ElementKind::Hex8, ElementKind::Tet4),
                         [](const auto& p) { return std::string(to_string(p.param)); });

}  // namespace
}  // namespace sinew
