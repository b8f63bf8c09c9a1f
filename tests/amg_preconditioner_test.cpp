// Algebraic multigrid (hypre BoomerAMG): the V-cycle is a symmetric positive definite
// preconditioner; PCG's iteration count stays nearly flat as a tetrahedral mesh is refined at
// nu = 0.49 while block-Jacobi's grows; it works on hexahedra too, with hypre's elasticity
// options (nodal coarsening, rigid-body modes when it knows the mesh) as well, rebuilds for each new matrix (sizes may change) and drives Newton
// through the settings; it needs the assembled matrix.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "elastic_bar_support.hpp"
#include "io_test_support.hpp"
#include "spd_test_support.hpp"
#include "sinew/assembly/problem.hpp"
#include "sinew/forms/elastic_form.hpp"
#include "sinew/material/families/corotational.hpp"
#include "sinew/mesh/lattice.hpp"
#include "sinew/mesh/selection.hpp"
#include "sinew/motion/prescribed_motion.hpp"
#include "sinew/solver/amg_preconditioner.hpp"
#include "sinew/solver/newton.hpp"
#include "sinew/solver/pcg_solver.hpp"

namespace sinew {
namespace {

using test::error_message;
using test::expect_contains;

// The bottom face pinned (tests/elastic_bar_support.hpp).
struct Bar : test::ElasticBar {
  Bar(const Eigen::Vector3i& cells, double nu, bool tets) : ElasticBar(cells, nu, tets, 0.0) {}
};

TEST(AmgPreconditioner, IsSymmetricPositiveDefiniteAndLeavesFixedDofs) {
  Bar bar(Eigen::Vector3i(5, 4, 6), 0.49, /*tets=*/true);
  const LinearOperator& H = bar.problem->hessian(bar.x);
  AmgPreconditioner M;
  M.setup(H, bar.context());
  EXPECT_GE(M.levels(), 2);
  EXPECT_FALSE(M.used_rigid_body_modes());  // off by default
  EXPECT_GT(M.operator_complexity(), 1.0);
  EXPECT_LT(M.operator_complexity(), 4.0);
  test::expect_symmetric_positive(M, bar.rhs(), bar.fixed, 1e-12);
  // The same preconditioner object rebuilds for another matrix, of another size.
  Bar small(Eigen::Vector3i(2, 2, 3), 0.3, /*tets=*/false);
  const LinearOperator& H2 = small.problem->hessian(small.x);
  M.setup(H2, small.context());
  Eigen::VectorXd z;
  M.apply(small.rhs(), z);
  EXPECT_EQ(z.size(), H2.rows());
  EXPECT_GT(z.dot(small.rhs()), 0.0);
}

TEST(AmgPreconditioner, IterationsStayNearlyFlatAsATetMeshIsRefined) {
  // nu = 0.49, each size twice the last (6 n^3 x 2 tetrahedra): AMG's PCG iterations grow
  // slowly while block-Jacobi's grow with the mesh.
  std::vector<int> amg, bj;
  for (int n : {4, 8, 16}) {
    Bar bar(Eigen::Vector3i(n, n, 2 * n), 0.49, /*tets=*/true);
    const LinearOperator& H = bar.problem->hessian(bar.x);
    const Eigen::VectorXd b = bar.rhs();
    PcgSolver pcg_amg(make_preconditioner("amg"), 5000);
    PcgSolver pcg_bj(make_preconditioner("block_jacobi"), 5000);
    Eigen::VectorXd x, Ax;
    const LinearSolveReport r = pcg_amg.solve(H, b, x, 1e-8, bar.context());
    ASSERT_TRUE(r.converged) << n;
    H.apply(x, Ax);
    EXPECT_LE((Ax - b).norm(), 1.01e-8 * b.norm());
    amg.push_back(r.iterations);
    bj.push_back(pcg_bj.solve(H, b, x, 1e-8, bar.context()).iterations);
    const auto& M = dynamic_cast<AmgPreconditioner&>(pcg_amg.preconditioner());
    std::printf("n = %d (%d tetrahedra): amg %d (%d levels, complexity %.2f), block_jacobi %d PCG iterations to 1e-8\n", n,
                12 * n * n * n, amg.back(), M.levels(), M.operator_complexity(), bj.back());
  }
  EXPECT_LE(amg[2], amg[1] * 3 / 2);
  EXPECT_GT(bj[2], 3 * amg[2]);
  EXPECT_GT(bj[2], bj[1]);
}

TEST(AmgPreconditioner, SolvesHexLatticesWithAndWithoutTheElasticityOptions) {
  Bar bar(Eigen::Vector3i(6, 6, 8), 0.45, /*tets=*/false);
  const LinearOperator& H = bar.problem->hessian(bar.x);
  const Eigen::VectorXd b = bar.rhs();
  AmgSettings elasticity;
  elasticity.nodal = 4;
  elasticity.rigid_body_modes = true;
  struct Case {
    const char* what;
    AmgSettings settings;
    bool with_mesh, expect_modes;
  };
  for (const Case& c : {Case{"default", AmgSettings{}, true, false}, Case{"nodal + rigid-body modes", elasticity, true, true},
                        Case{"nodal, no mesh", elasticity, false, false}}) {
    PcgSolver pcg(std::make_unique<AmgPreconditioner>(c.settings), 1000);
    Eigen::VectorXd x, Ax;
    const SolverContext context{c.with_mesh ? bar.disc : nullptr, bar.problem->fixed()};
    const LinearSolveReport r = pcg.solve(H, b, x, 1e-10, context);
    EXPECT_TRUE(r.converged) << c.what;
    H.apply(x, Ax);
    EXPECT_LE((Ax - b).norm(), 1.01e-10 * b.norm()) << c.what;
    const auto& M = dynamic_cast<AmgPreconditioner&>(pcg.preconditioner());
    EXPECT_EQ(M.used_rigid_body_modes(), c.expect_modes) << c.what;
    std::printf("6 x 6 x 8 hexahedra, nu = 0.45, amg %s: %d PCG iterations to 1e-10, operator complexity %.2f\n", c.what,
                r.iterations, M.operator_complexity());
  }
}

// The vertices on the plane z = height (outward normal (0, 0, normal_z)) moved by `motion`.
KinematicCondition face(const Eigen::MatrixX3d& rest, double height, double normal_z, RigidMotion motion, const std::string& name) {
  KinematicCondition c;
  c.vertices = select_vertices(rest, PlaneSelector{{0, 0, height}, {0, 0, normal_z}}, name);
  c.motion = std::move(motion);
  c.source = name;
  return c;
}

TEST(AmgPreconditioner, DrivesNewtonThroughTheSettingsOnTetrahedra) {
  Bar bar(Eigen::Vector3i(3, 3, 6), 0.45, /*tets=*/true);
  const Eigen::MatrixX3d& rest = bar.disc->mesh().vertices;
  const std::vector<KinematicCondition> bcs = {face(rest, 0.0, -1.0, Pinned{}, "bottom"),
                                               face(rest, 6.0, 1.0, Translation{{0.3, 0, 0.5}}, "top")};
  std::vector<char> fixed(bar.x.size(), 0);
  apply_kinematics(bcs, bar.disc->mesh().vertices, 1.0, bar.x, fixed);
  bar.problem->set_fixed(fixed);
  LinearSolverSettings ls;
  ls.kind = "pcg";
  ls.preconditioner = "amg";
  auto linear = make_linear_solver(ls);
  EXPECT_EQ(linear->name(), "pcg-amg");
  NewtonSettings ns;
  ns.test = ConvergenceTest::Absolute;
  ns.absolute_tolerance = 1e-8;
  ns.linear_tolerance = 1e-8;
  const NewtonReport r = newton_solve(*bar.problem, bar.x, *linear, ns);
  EXPECT_TRUE(r.converged) << r.failure;
}

TEST(AmgPreconditioner, NeedsTheAssembledMatrix) {
  Bar bar(Eigen::Vector3i(2, 2, 2), 0.3, /*tets=*/true);
  const LinearOperator& H = bar.problem->hessian(bar.x);
  AmgPreconditioner M;
  expect_contains(error_message([&] { M.setup(test::WithoutMatrix(H), bar.context()); }), {"amg", "assembled matrix"});
  Eigen::VectorXd z;
  expect_contains(error_message([&] { M.apply(bar.rhs(), z); }), {"amg", "before setup"});
}

}  // namespace
}  // namespace sinew
