// The matrix-free Newton operator (Problem::set_matrix_free) against the assembled one: same
// products and diagonal blocks to single precision, with Dirichlet DOFs, a rotated vertex frame
// and an assembled second form; the same Newton solution; the memory it keeps.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <random>

#include "sinew/assembly/problem.hpp"
#include "sinew/forms/elastic_form.hpp"
#include "sinew/forms/inertia_form.hpp"
#include "sinew/material/spec.hpp"
#include "sinew/mesh/lattice.hpp"
#include "sinew/solver/linear_solver.hpp"
#include "sinew/solver/newton.hpp"

namespace sinew {
namespace {

std::shared_ptr<const Material> stable_neo_hookean() {
  MaterialSpec spec;
  spec.family = "stable_neo_hookean";
  spec.target = YoungPoisson{1e5, 0.45};
  return build_material(spec);
}

struct Case {
  std::shared_ptr<Discretization> disc;
  std::unique_ptr<Problem> problem;
  Eigen::VectorXd x;
};

Case make_case(ElementKind kind, bool with_inertia) {
  VolumeMesh mesh = box_lattice(Eigen::Vector3d::Zero(), Eigen::Vector3d(1.0, 0.7, 0.5), Eigen::Vector3i(4, 3, 2));
  if (kind == ElementKind::Tet4) mesh = tetrahedralize_hexes(mesh);
  Case s;
  s.disc = std::make_shared<Discretization>(mesh);
  s.problem = std::make_unique<Problem>(mesh.num_vertices());
  s.problem->add_form(std::make_shared<ElasticForm>(s.disc, stable_neo_hookean(), Projection::Clamp));
  if (with_inertia)
    s.problem->add_form(std::make_shared<InertiaForm>(std::make_shared<MassMatrix>(*s.disc, 1000.0, MassKind::Consistent), 0.01));
  std::vector<char> fixed(static_cast<size_t>(s.problem->num_dofs()), 0);
  for (Eigen::Index v = 0; v < mesh.num_vertices(); ++v)
    if (mesh.vertices(v, 0) < 1e-12 || mesh.vertices(v, 0) > 1.0 - 1e-12) fixed[3 * v] = fixed[3 * v + 1] = fixed[3 * v + 2] = 1;
  fixed[3 * 7 + 1] = 1;  // one component of another vertex
  s.problem->set_fixed(fixed);
  const double c = std::cos(0.4), sn = std::sin(0.4);
  Mat3 Q;
  Q << c, -sn, 0, sn, c, 0, 0, 0, 1;
  s.problem->set_vertex_frames({{7, Q}});
  // Stretched, twisted and perturbed: many quadrature points indefinite, some inverted.
  s.x = mesh.rest_positions();
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(-0.12, 0.12);
  for (Eigen::Index v = 0; v < mesh.num_vertices(); ++v) {
    s.x(3 * v) *= 1.6;
    for (int i = 0; i < 3; ++i) s.x(3 * v + i) += u(rng);
  }
  return s;
}

// The matrix-free product runs over coloured runs of consecutive elements in parallel, each
// run in order and the colours one after another: the same bits with one thread or two.
TEST(MatrixFreeProduct, IsBitwiseTheSameWithOneThreadOrTwo) {
  const VolumeMesh mesh = box_lattice(Eigen::Vector3d::Zero(), Eigen::Vector3d(1.0, 0.8, 0.6), Eigen::Vector3i(12, 10, 8));
  auto disc = std::make_shared<Discretization>(mesh);
  Problem problem(mesh.num_vertices());
  problem.add_form(std::make_shared<ElasticForm>(disc, stable_neo_hookean(), Projection::Clamp));
  problem.set_matrix_free(true);
  Eigen::VectorXd x = mesh.rest_positions();
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-0.02, 0.02);
  for (Eigen::Index i = 0; i < x.size(); ++i) x(i) += u(rng);
  const LinearOperator& op = problem.hessian(x);
  ASSERT_EQ(op.matrix(), nullptr);
  const Eigen::VectorXd p = Eigen::VectorXd::LinSpaced(x.size(), -1.0, 1.0);
  auto product = [&](int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    Eigen::VectorXd y;
    op.apply(p, y);
    return y;
  };
  const Eigen::VectorXd one = product(1), two = product(2);
  EXPECT_GT(one.norm(), 0.0);
  EXPECT_TRUE(one == two);
}

class MatrixFreeHessian : public ::testing::TestWithParam<std::tuple<ElementKind, bool>> {};

TEST_P(MatrixFreeHessian, ProductsAndDiagonalMatchTheAssembledOperator) {
  const auto [kind, exact] = GetParam();
  for (const bool inertia : {false, true}) {
    Case s = make_case(kind, inertia);
    const Eigen::MatrixXd A(*s.problem->hessian(s.x, exact).matrix());
    const std::size_t assembled_bytes = s.problem->hessian_bytes();
    s.problem->set_matrix_free(true);
    const LinearOperator& op = s.problem->hessian(s.x, exact);
    EXPECT_EQ(op.matrix(), nullptr);
    EXPECT_EQ(op.rows(), A.rows());
    std::mt19937 rng(9);
    std::normal_distribution<double> n(0.0, 1.0);
    for (int trial = 0; trial < 3; ++trial) {
      Eigen::VectorXd p(A.rows()), y;
      for (Eigen::Index i = 0; i < p.size(); ++i) p(i) = n(rng);
      op.apply(p, y);
      const Eigen::VectorXd expected = A * p;
      // Single-precision element matrices: ~1e-7 of the largest terms.
      EXPECT_LE((y - expected).norm(), 2e-6 * A.norm() * p.norm()) << "inertia " << inertia;
    }
    for (Eigen::Index v = 0; v < A.rows() / 3; ++v) {
      EXPECT_LE((op.diagonal_block(v) - A.block<3, 3>(3 * v, 3 * v)).norm(), 2e-6 * A.norm()) << "vertex " << v;
    }
    if (!inertia) {
      EXPECT_LT(s.problem->hessian_bytes(), assembled_bytes);
    }
  }
}

// What multigrid's Galerkin product reads (LinearOperator::element_matrices): the elastic
// elements, then the assembled inertia's blocks, in local frames; summed, they are the operator on
// the free DOFs (its Dirichlet identity rows are left out). Same structure id for the next
// Newton matrix.
TEST_P(MatrixFreeHessian, ElementMatricesSumToTheOperatorOnTheFreeDofs) {
  const auto [kind, exact] = GetParam();
  Case s = make_case(kind, true);
  const Eigen::MatrixXd A(*s.problem->hessian(s.x, exact).matrix());
  s.problem->set_matrix_free(true);
  const LinearOperator& op = s.problem->hessian(s.x, exact);
  const ElementMatrices* elements = op.element_matrices();
  ASSERT_NE(elements, nullptr);
  EXPECT_GT(elements->count(), s.disc->num_elements());  // the inertia's blocks come after the elements
  Eigen::MatrixXd sum = Eigen::MatrixXd::Zero(A.rows(), A.cols());
  ElementMatrix K;
  for (Eigen::Index e = 0; e < elements->count(); ++e) {
    int v[kMaxElementMatrixVertices];
    const int n = elements->vertices(e, v);
    elements->matrix(e, K);
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < n; ++b) sum.block<3, 3>(3 * v[a], 3 * v[b]) += K.block<3, 3>(3 * a, 3 * b);
  }
  const std::vector<char>& fixed = s.problem->fixed();
  for (Eigen::Index i = 0; i < A.rows(); ++i)
    for (Eigen::Index j = 0; j < A.cols(); ++j)
      if (fixed[static_cast<size_t>(i)] || fixed[static_cast<size_t>(j)]) sum(i, j) = A(i, j);
  EXPECT_LE((sum - A).norm(), 2e-6 * A.norm());
  const std::uint64_t id = elements->structure_id();
  EXPECT_EQ(s.problem->hessian(s.x, exact).element_matrices()->structure_id(), id);
}

TEST_P(MatrixFreeHessian, NewtonReachesTheAssembledSolution) {
  const auto [kind, exact_tail] = GetParam();
  LinearSolverSettings linear;
  linear.kind = "pcg";
  NewtonSettings settings;
  settings.exact_tail = exact_tail;
  settings.linear_tolerance = 1e-6;
  settings.residual_tolerance = 1e-9;
  Eigen::VectorXd solutions[2];
  for (const bool matrix_free : {false, true}) {
    Case s = make_case(kind, false);
    s.problem->set_matrix_free(matrix_free);
    // Start from the rest shape with one clamped end moved: a stretch to solve.
    Eigen::VectorXd x = s.disc->mesh().rest_positions();
    for (Eigen::Index v = 0; v < s.disc->mesh().num_vertices(); ++v)
      if (x(3 * v) > 1.0 - 1e-12) x(3 * v) += 0.3;
    auto solver = make_linear_solver(linear);
    const NewtonReport r = newton_solve(*s.problem, x, *solver, settings);
    ASSERT_TRUE(r.converged) << r.failure;
    solutions[matrix_free ? 1 : 0] = x;
  }
  EXPECT_LE((solutions[1] - solutions[0]).norm(), 1e-6 * solutions[0].norm());
}

INSTANTIATE_TEST_SUITE_P(KindsAndHessians, MatrixFreeHessian,
                         ::testing::Combine(::testing::Values(ElementKind::Hex8, ElementKind::Tet4), ::testing::Bool()),
                         [](const auto& p) {
                           return std::string(to_string(std::get<0>(p.param))) +
                                  (std::get<1>(p.param) ? "Exact" : "Projected");
                         });

}  // namespace
}  // namespace sinew
