// Preconditioners through the registry: each built-in one solves small SPD systems (also with
// fixed DOFs) through PCG, the iteration counts order as expected (a Cholesky factorisation of
// the same matrix converges in one), the lagged factorisation is reused and refreshed, the
// registry rejects bad names, and a preconditioner registered here (not in the library) is
// reached through the settings and receives the Newton solve's context.
#include <gtest/gtest.h>

#include "spd_test_support.hpp"

#include <algorithm>
#include <map>
#include <random>

#include "io_test_support.hpp"
#include "sinew/forms/elastic_form.hpp"
#include "sinew/material/families/corotational.hpp"
#include "sinew/mesh/lattice.hpp"
#include "sinew/mesh/selection.hpp"
#include "sinew/motion/prescribed_motion.hpp"
#include "sinew/solver/diagonal_preconditioners.hpp"
#include "sinew/solver/lagged_cholesky_preconditioner.hpp"
#include "sinew/solver/newton.hpp"
#include "sinew/solver/pcg_solver.hpp"
#include "sinew/solver/preconditioner.hpp"

namespace sinew {
namespace {

using test::error_message;
using test::expect_contains;

const std::vector<std::string> kBuiltIn = {"jacobi", "block_jacobi", "lagged_cholesky", "multigrid", "amg"};

// A random SPD matrix with 3x3 vertex blocks (B^T B + 0.1 I), with the rows and columns of the
// flagged DOFs replaced by the identity, as Problem::hessian does for fixed DOFs.
Eigen::SparseMatrix<double> random_spd(int vertices, unsigned seed, const std::vector<char>& fixed) {
  Eigen::SparseMatrix<double> A = test::random_spd(vertices, seed);
  for (int c = 0; c < A.outerSize(); ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, c); it; ++it)
      if (!fixed.empty() && (fixed[it.row()] || fixed[it.col()])) it.valueRef() = it.row() == it.col() ? 1.0 : 0.0;
  return A;
}

// The Hessian of a linear co-rotational cube lattice at rest (cells^3 hexahedra), bottom face
// fixed: a small elasticity system as Newton sees it.
struct LatticeSystem {
  std::shared_ptr<Discretization> disc;
  std::unique_ptr<Problem> problem;
  Eigen::VectorXd x;
  explicit LatticeSystem(int cells, double nu = 0.3) {
    disc = std::make_shared<Discretization>(
        box_lattice(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), Eigen::Vector3i::Constant(cells)));
    problem = std::make_unique<Problem>(disc->mesh().num_vertices());
    problem->add_form(std::make_shared<ElasticForm>(disc, std::make_shared<LinearCorotational>(1e3, nu)));
    problem->set_discretization(disc);
    x = disc->mesh().rest_positions();
    std::vector<char> fixed(x.size(), 0);
    for (int v : select_vertices(disc->mesh().vertices, PlaneSelector{{0, 0, 0}, {0, 0, -1}}, "bottom"))
      for (int i = 0; i < 3; ++i) fixed[3 * v + i] = 1;
    problem->set_fixed(fixed);
  }
  SolverContext context() const { return {disc, problem->fixed()}; }
};

// A view of a matrix without matrix(): what a matrix-free operator looks like to a preconditioner.
class MatrixFreeView final : public LinearOperator {
 public:
  explicit MatrixFreeView(const Eigen::SparseMatrix<double>& A) : op_(A) {}
  Eigen::Index rows() const override { return op_.rows(); }
  void apply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const override { op_.apply(x, y); }
  Mat3 diagonal_block(Eigen::Index v) const override { return op_.diagonal_block(v); }

 private:
  SparseOperator op_;
};

LinearSolveReport pcg_solve(const std::string& preconditioner, const LinearOperator& A, const Eigen::VectorXd& b,
                            Eigen::VectorXd& x, double tolerance, const SolverContext& context = {}) {
  PcgSolver pcg(make_preconditioner(preconditioner), 10000);
  return pcg.solve(A, b, x, tolerance, context);
}

TEST(Preconditioner, RegistryListsTheBuiltInOnes) {
  const std::vector<std::string> names = registered_preconditioners();
  ASSERT_GE(names.size(), kBuiltIn.size());
  EXPECT_TRUE(std::equal(kBuiltIn.begin(), kBuiltIn.end(), names.begin()));  // built-in ones first, in order
  for (const std::string& name : kBuiltIn) {
    EXPECT_EQ(make_preconditioner(name)->name(), name);
    EXPECT_FALSE(preconditioner_description(name).empty()) << name;
  }
  LinearSolverSettings s;
  s.kind = "pcg";
  EXPECT_EQ(make_linear_solver(s)->name(), "pcg-block-jacobi");  // the default, named as before
  s.preconditioner = "jacobi";
  EXPECT_EQ(make_linear_solver(s)->name(), "pcg-jacobi");
  s.preconditioner = "lagged_cholesky";
  EXPECT_EQ(make_linear_solver(s)->name(), "pcg-lagged-cholesky");
  s.preconditioner = "amg";
  EXPECT_EQ(make_linear_solver(s)->name(), "pcg-amg");
}

TEST(Preconditioner, RegistryRejectsUnknownAndDuplicateNames) {
  const std::string unknown = error_message([] { make_preconditioner("ilu"); });
  expect_contains(unknown, {"unknown preconditioner 'ilu'", "registered: jacobi, block_jacobi, lagged_cholesky, multigrid, amg"});
  LinearSolverSettings s;
  s.kind = "pcg";
  s.preconditioner = "ilu";
  expect_contains(error_message([&] { make_linear_solver(s); }), {"unknown preconditioner 'ilu'", "block_jacobi", "amg"});
  auto factory = [] { return make_preconditioner("jacobi"); };
  expect_contains(error_message([&] { register_preconditioner("block_jacobi", "again", factory); }),
                  {"'block_jacobi' is already registered"});
  expect_contains(error_message([&] { register_preconditioner("", "nameless", factory); }), {"needs a name"});
  expect_contains(error_message([&] { register_preconditioner("no_factory", "", PreconditionerFactory{}); }),
                  {"'no_factory' has no factory"});
  const std::vector<std::string> names = registered_preconditioners();
  EXPECT_EQ(std::count(names.begin(), names.end(), "block_jacobi"), 1);
  EXPECT_EQ(std::count(names.begin(), names.end(), "no_factory"), 0);
  EXPECT_EQ(std::count(names.begin(), names.end(), ""), 0);
  // A factory that makes nothing is caught when used.
  static bool registered = false;
  if (!registered) register_preconditioner("test_null", "makes nothing", [] { return std::unique_ptr<Preconditioner>(); });
  registered = true;
  expect_contains(error_message([] { make_preconditioner("test_null"); }), {"'test_null' made no preconditioner"});
}

TEST(Preconditioner, EachOneSolvesAnSpdSystemWithFixedDofs) {
  const int vertices = 300;
  std::vector<char> fixed(3 * vertices, 0);
  for (int v = 0; v < vertices; v += 7)
    for (int i = 0; i < 3; ++i) fixed[3 * v + i] = 1;
  const Eigen::SparseMatrix<double> A = random_spd(vertices, 11, fixed);
  const SparseOperator op(A);
  const Eigen::VectorXd b = Eigen::VectorXd::Random(A.rows());
  Eigen::VectorXd direct;
  ASSERT_TRUE(make_linear_solver({})->solve(op, b, direct, 0.0).converged);
  const SolverContext context{nullptr, fixed};
  for (const std::string& name : kBuiltIn) {
    Eigen::VectorXd x;
    const LinearSolveReport r = pcg_solve(name, op, b, x, 1e-10, context);
    EXPECT_TRUE(r.converged) << name;
    EXPECT_LE((A * x - b).norm(), 1.01e-10 * b.norm()) << name;
    EXPECT_LE((x - direct).norm(), 1e-6 * direct.norm()) << name;
    for (Eigen::Index i = 0; i < A.rows(); ++i)
      if (fixed[i]) {
        EXPECT_NEAR(x(i), b(i), 1e-8 * b.norm()) << name << " DOF " << i;
      }
  }
  // A mask of the wrong size is an error, not a silent misreading.
  Eigen::VectorXd x;
  const std::vector<char> short_mask(fixed.begin(), fixed.end() - 3);
  expect_contains(error_message([&] { pcg_solve("jacobi", op, b, x, 1e-8, {nullptr, short_mask}); }),
                  {"fixed-DOF mask does not match"});
}

TEST(Preconditioner, IterationCountsOnALatticeElasticitySystem) {
  LatticeSystem s(6, 0.45);
  const LinearOperator& H = s.problem->hessian(s.x);
  Eigen::VectorXd b = Eigen::VectorXd::Random(H.rows());
  for (Eigen::Index i = 0; i < b.size(); ++i)
    if (s.problem->fixed()[i]) b(i) = 0.0;
  std::map<std::string, int> iterations;
  for (const std::string& name : kBuiltIn) {
    Eigen::VectorXd x, Ax;
    const LinearSolveReport r = pcg_solve(name, H, b, x, 1e-8, s.context());
    ASSERT_TRUE(r.converged) << name;
    H.apply(x, Ax);
    EXPECT_LE((Ax - b).norm(), 1.01e-8 * b.norm()) << name;
    iterations[name] = r.iterations;
  }
  std::printf("PCG iterations to 1e-8, 6^3 hex lattice, nu = 0.45: jacobi %d, block_jacobi %d, lagged_cholesky %d\n",
              iterations["jacobi"], iterations["block_jacobi"], iterations["lagged_cholesky"]);
  EXPECT_EQ(iterations["lagged_cholesky"], 1);  // a factorisation of the same matrix
  EXPECT_GT(iterations["block_jacobi"], 10);
  EXPECT_LE(iterations["block_jacobi"], iterations["jacobi"]);
}

TEST(Preconditioner, LaggedCholeskyIsReusedForNearbyMatricesAndRefreshed) {
  const Eigen::SparseMatrix<double> A = random_spd(200, 5, {});
  Eigen::SparseMatrix<double> A2 = A;
  A2.diagonal() *= 1.05;  // the next Newton matrix: same pattern, nearby values
  const Eigen::VectorXd b = Eigen::VectorXd::Random(A.rows());
  PcgSolver pcg(std::make_unique<LaggedCholeskyPreconditioner>(), 1000);
  auto& P = dynamic_cast<LaggedCholeskyPreconditioner&>(pcg.preconditioner());
  Eigen::VectorXd x;
  EXPECT_EQ(pcg.solve(SparseOperator(A), b, x, 1e-10).iterations, 1);
  EXPECT_TRUE(P.exact());
  EXPECT_EQ(P.factorizations(), 1);
  const LinearSolveReport r = pcg.solve(SparseOperator(A2), b, x, 1e-10);
  EXPECT_FALSE(P.exact());  // the factorisation of A preconditions A2
  EXPECT_EQ(P.factorizations(), 1);
  EXPECT_TRUE(r.converged);
  EXPECT_GT(r.iterations, 1);
  EXPECT_LE((A2 * x - b).norm(), 1.01e-10 * b.norm());
  // Solves until the CG work reaches a factorisation's cost; then the next setup refactorises.
  int solves = 0;
  while (P.factorizations() == 1 && solves < 10000) {
    pcg.solve(SparseOperator(A2), b, x, 1e-10);
    ++solves;
  }
  EXPECT_EQ(P.factorizations(), 2);
  EXPECT_TRUE(P.exact());
  EXPECT_EQ(pcg.solve(SparseOperator(A2), b, x, 1e-10).iterations, 1);
  // A changed pattern is refactorised at once.
  Eigen::SparseMatrix<double> A3 = random_spd(200, 6, {});
  EXPECT_EQ(pcg.solve(SparseOperator(A3), b, x, 1e-10).iterations, 1);
  EXPECT_EQ(P.factorizations(), 3);
  // refresh_cost_factor 0 refactorises at every solve.
  PcgSolver exact(std::make_unique<LaggedCholeskyPreconditioner>(LaggedCholeskySettings{0.0}), 1000);
  EXPECT_EQ(exact.solve(SparseOperator(A), b, x, 1e-10).iterations, 1);
  EXPECT_EQ(exact.solve(SparseOperator(A2), b, x, 1e-10).iterations, 1);
  EXPECT_EQ(dynamic_cast<LaggedCholeskyPreconditioner&>(exact.preconditioner()).factorizations(), 2);
  // It needs an assembled matrix.
  expect_contains(error_message([&] { pcg.solve(MatrixFreeView(A), b, x, 1e-8); }),
                  {"lagged_cholesky", "needs an assembled matrix"});
  // The diagonal ones do not.
  EXPECT_TRUE(pcg_solve("block_jacobi", MatrixFreeView(A), b, x, 1e-8).converged);
}

// Registered by this test, not by the library: proves that a new preconditioner needs no change
// to PCG or the settings, and shows what the Newton solve hands it.
struct Recorded {
  int setups = 0;
  const Discretization* discretization = nullptr;
  Eigen::Vector3i lattice_cells = Eigen::Vector3i::Zero();
  std::vector<char> fixed;
};
Recorded recorded;

class RecordingPreconditioner final : public Preconditioner {
 public:
  std::string name() const override { return "test_recording"; }
  void setup(const LinearOperator& A, const SolverContext& context) override {
    ++recorded.setups;
    recorded.discretization = context.discretization.get();
    recorded.lattice_cells = context.lattice() ? context.lattice()->cells : Eigen::Vector3i::Zero();
    recorded.fixed.assign(context.fixed.begin(), context.fixed.end());
    inner_.setup(A, context);
  }
  void apply(const Eigen::VectorXd& r, Eigen::VectorXd& z) override { inner_.apply(r, z); }

 private:
  DiagonalPreconditioner inner_{DiagonalPreconditioner::Blocks::Vertex3};
};

TEST(Preconditioner, ARegisteredOneGetsTheNewtonSolvesContext) {
  static bool registered = false;
  if (!registered)
    register_preconditioner("test_recording", "block-Jacobi that records its context",
                            [] { return std::make_unique<RecordingPreconditioner>(); });
  registered = true;
  recorded = {};
  LatticeSystem s(3);
  // Pull the top face up so that Newton has work to do.
  std::vector<KinematicCondition> bcs;
  bcs.push_back({select_vertices(s.disc->mesh().vertices, PlaneSelector{{0, 0, 0}, {0, 0, -1}}, "bottom"), Pinned{}, "bottom",
                 {true, true, true}, {}});
  bcs.push_back({select_vertices(s.disc->mesh().vertices, PlaneSelector{{0, 0, 1}, {0, 0, 1}}, "top"),
                 Translation{{0, 0, 0.1}}, "top", {true, true, true}, {}});
  std::vector<char> fixed(s.x.size(), 0);
  apply_kinematics(bcs, s.disc->mesh().vertices, 1.0, s.x, fixed);
  s.problem->set_fixed(fixed);
  LinearSolverSettings ls;
  ls.kind = "pcg";
  ls.preconditioner = "test_recording";
  auto linear = make_linear_solver(ls);
  EXPECT_EQ(linear->name(), "pcg-test-recording");
  NewtonSettings ns;
  ns.test = ConvergenceTest::Absolute;
  ns.absolute_tolerance = 1e-8;
  ns.linear_tolerance = 1e-8;
  const NewtonReport r = newton_solve(*s.problem, s.x, *linear, ns);
  EXPECT_TRUE(r.converged) << r.failure;
  // One setup per linear solve: one per Newton iteration, and one more for each true-Hessian
  // solve that failed and was solved again with the projected Hessian.
  EXPECT_EQ(recorded.setups, r.iterations + r.exact_fallbacks);
  EXPECT_EQ(recorded.discretization, s.disc.get());
  EXPECT_EQ(recorded.lattice_cells, Eigen::Vector3i(3, 3, 3));
  EXPECT_EQ(recorded.fixed, fixed);
}

}  // namespace
}  // namespace sinew
