// Derivatives of the inertia, Rayleigh damping and penalty contact forms against finite
// differences, and the obstacle geometry (distance, normal = its gradient, normal derivative).
#include <gtest/gtest.h>

#include <random>

#include "dynamics_test_support.hpp"
#include "sinew/forms/penalty_contact_form.hpp"
#include "sinew/forms/elastic_form.hpp"
#include "sinew/forms/inertia_form.hpp"
#include "sinew/material/families/stable_neo_hookean.hpp"
#include "sinew/mesh/lattice.hpp"

namespace sinew {
namespace {

using testing_support::form_derivative_errors;

std::shared_ptr<Discretization> small_disc(ElementKind kind) {
  VolumeMesh m = box_lattice(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1.0, 0.8, 0.6), Eigen::Vector3i(2, 2, 1));
  return std::make_shared<Discretization>(kind == ElementKind::Hex8 ? m : tetrahedralize_hexes(m));
}

Eigen::VectorXd perturbed(const Eigen::VectorXd& x, double amount, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-amount, amount);
  Eigen::VectorXd y = x;
  for (Eigen::Index i = 0; i < y.size(); ++i) y(i) += u(rng);
  return y;
}

class DynamicsForms : public ::testing::TestWithParam<ElementKind> {};

TEST_P(DynamicsForms, InertiaMatchesFiniteDifferencesForBothMasses) {
  const auto disc = small_disc(GetParam());
  const Eigen::VectorXd rest = disc->mesh().rest_positions();
  for (MassKind kind : {MassKind::Lumped, MassKind::Consistent}) {
    auto mass = std::make_shared<MassMatrix>(*disc, 1200.0, kind);
    InertiaForm inertia(mass, 0.01);
    inertia.set_prediction(rest, perturbed(Eigen::VectorXd::Zero(rest.size()), 1.0, 1));
    const auto e = form_derivative_errors(inertia, perturbed(rest, 0.1, 2), disc->mesh().num_vertices());
    EXPECT_LT(e.gradient, 1e-7);
    EXPECT_LT(e.hessian, 1e-7);
    EXPECT_LT(e.asymmetry, 1e-12);
    // Total mass: sum of the lumped masses = density * volume; the consistent matrix has the
    // same row sums, so both give the same kinetic energy for a rigid translation.
    EXPECT_NEAR(mass->lumped().sum(), 1200.0 * 0.48, 1e-9);
    const Eigen::VectorXd v = Eigen::Vector3d(1, 2, 3).replicate(rest.size() / 3, 1);
    EXPECT_NEAR(mass->kinetic_energy(v), 0.5 * 1200.0 * 0.48 * 14.0, 1e-8);
  }
}

TEST_P(DynamicsForms, RayleighDampingMatchesFiniteDifferences) {
  const auto disc = small_disc(GetParam());
  const Eigen::VectorXd rest = disc->mesh().rest_positions();
  auto mass = std::make_shared<MassMatrix>(*disc, 1000.0, MassKind::Consistent);
  auto elastic = std::make_shared<ElasticForm>(disc, std::make_shared<StableNeoHookean>(5e4, 1e4));
  DampingForm damping(mass, elastic, disc->mesh().num_vertices(), 0.5, 0.01, 0.02);
  damping.begin_step(perturbed(rest, 0.05, 3));
  const Eigen::VectorXd x = perturbed(rest, 0.1, 4);
  const auto e = form_derivative_errors(damping, x, disc->mesh().num_vertices());
  EXPECT_LT(e.gradient, 1e-7);
  EXPECT_LT(e.hessian, 1e-7);
  EXPECT_LT(e.asymmetry, 1e-10);
  EXPECT_GT(damping.value(x), 0.0);  // dissipation is non-negative
}

INSTANTIATE_TEST_SUITE_P(HexAndTet, DynamicsForms, ::testing::Values(ElementKind::Hex8, ElementKind::Tet4));

std::vector<std::shared_ptr<const ObstacleShape>> all_shapes() {
  return {std::make_shared<PlaneObstacle>(Eigen::Vector3d(0, 0, 0.1), Eigen::Vector3d(0.2, 0.1, 1)),
          std::make_shared<SphereObstacle>(Eigen::Vector3d(0.1, 0, 0), 0.7),
          std::make_shared<CapsuleObstacle>(Eigen::Vector3d(-0.5, 0, 0), Eigen::Vector3d(0.4, 0.2, 0.1), 0.5),
          std::make_shared<CylinderObstacle>(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0.3, 0), 0.6, 1.4),
          std::make_shared<BoxObstacle>(Eigen::Vector3d(-0.6, -0.5, -0.4), Eigen::Vector3d(0.5, 0.6, 0.7))};
}

TEST(Obstacles, DistanceNormalAndCurvatureAreConsistent) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.2, 1.2);
  for (const auto& shape : all_shapes()) {
    int inside = 0, outside = 0;
    for (int trial = 0; trial < 400; ++trial) {
      const Eigen::Vector3d p(u(rng), u(rng), u(rng));
      const SurfaceQuery q = shape->query(p);
      SCOPED_TRACE(shape->type());
      EXPECT_NEAR(q.normal.norm(), 1.0, 1e-12);
      // The closest point lies on the surface, at |distance| from p.
      EXPECT_NEAR(shape->query(q.closest).distance, 0.0, 1e-10);
      EXPECT_NEAR((p - q.closest).norm(), std::abs(q.distance), 1e-10);
      // normal = grad distance; inside, d(normal)/dp = the Hessian of the distance. Points near
      // a kink of the distance (medial axis, rims) are skipped by comparing one-sided slopes.
      const double h = 1e-6;
      Eigen::Vector3d grad;
      Mat3 dn;
      bool smooth = true;
      for (int i = 0; i < 3; ++i) {
        const Eigen::Vector3d e = h * Eigen::Vector3d::Unit(i);
        const SurfaceQuery qp = shape->query(p + e), qm = shape->query(p - e);
        const double fwd = (qp.distance - q.distance) / h, bwd = (q.distance - qm.distance) / h;
        if (std::abs(fwd - bwd) > 1e-4 || (qp.normal - qm.normal).norm() > 1e-3) smooth = false;
        grad(i) = (qp.distance - qm.distance) / (2 * h);
        dn.col(i) = (qp.normal - qm.normal) / (2 * h);
      }
      if (!smooth) continue;
      EXPECT_LT((grad - q.normal).norm(), 1e-6);
      if (q.distance < 0.0) {
        ++inside;
        EXPECT_LT((dn - q.normal_derivative).norm(), 1e-4 * std::max(1.0, dn.norm()));
      } else {
        ++outside;
      }
    }
    EXPECT_GT(inside, 20) << shape->type();
    EXPECT_GT(outside, 20) << shape->type();
  }
}

TEST(Obstacles, KnownDistances) {
  const CylinderObstacle cyl(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0, 0, 2), 1.0, 2.0);
  EXPECT_NEAR(cyl.query(Eigen::Vector3d(0.5, 0, 0)).distance, -0.5, 1e-14);  // side nearer
  EXPECT_NEAR(cyl.query(Eigen::Vector3d(0, 0, 0.8)).distance, -0.2, 1e-14);  // cap nearer
  EXPECT_NEAR(cyl.query(Eigen::Vector3d(2, 0, 0)).distance, 1.0, 1e-14);
  EXPECT_NEAR(cyl.query(Eigen::Vector3d(4, 0, 5)).distance, 5.0, 1e-14);  // to the rim (3, 4)
  const BoxObstacle box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 2, 3));
  EXPECT_NEAR(box.query(Eigen::Vector3d(0.5, 0.3, 1.5)).distance, -0.3, 1e-14);
  EXPECT_NEAR(box.query(Eigen::Vector3d(2, 3, 1)).distance, std::sqrt(2.0), 1e-14);
  const CapsuleObstacle cap(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0), 0.5);
  EXPECT_NEAR(cap.query(Eigen::Vector3d(0.5, 0.2, 0)).distance, -0.3, 1e-14);
  EXPECT_NEAR(cap.query(Eigen::Vector3d(-1, 0, 0)).distance, 0.5, 1e-14);
}

TEST(Obstacles, KeyframedPathMovesQueriesAndPoints) {
  Keyframes path;
  path.keys.push_back({0.0, Eigen::Quaterniond::Identity(), Eigen::Vector3d::Zero()});
  path.keys.push_back({2.0, Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ())),
                       Eigen::Vector3d(0, 0, 1)});
  const Obstacle o("pusher", std::make_shared<BoxObstacle>(Eigen::Vector3d(0, -0.1, -0.1), Eigen::Vector3d(1, 0.1, 0.1)),
                   path);
  // At frame 2 the bar points along +y and sits one unit up.
  EXPECT_LT(o.query(Eigen::Vector3d(0, 0.5, 1), 2.0).distance, 0.0);
  EXPECT_GT(o.query(Eigen::Vector3d(0.5, 0, 0), 2.0).distance, 0.0);
  EXPECT_LT(o.query(Eigen::Vector3d(0.5, 0, 0), 0.0).distance, 0.0);
  // Halfway: slerp by 45 degrees, lerp half a unit.
  const Eigen::Vector3d moved = Eigen::Vector3d(0.5, 0, 0) + o.displacement(Eigen::Vector3d(0.5, 0, 0), 0.0, 1.0);
  EXPECT_LT((moved - Eigen::Vector3d(0.5 * std::sqrt(0.5), 0.5 * std::sqrt(0.5), 0.5)).norm(), 1e-12);
  EXPECT_TRUE(o.moves());
  // Velocity (frames of 0.5 s): 0.5 m per frame up and 45 degrees per frame about z.
  const Eigen::Vector3d w(0, 0, M_PI / 4 / 0.5);  // rad/s
  const Eigen::Vector3d at = Eigen::Vector3d(1, 0, 0);
  EXPECT_LT((o.velocity(at, 0.0, 0.5) - (Eigen::Vector3d(0, 0, 1.0) + w.cross(at))).norm(), 1e-5);
  const Obstacle still("ground", std::make_shared<PlaneObstacle>(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ()));
  EXPECT_FALSE(still.moves());
  EXPECT_EQ(still.velocity(at, 3.0, 0.1), Eigen::Vector3d::Zero());
}

TEST(PenaltyContact, MatchesFiniteDifferencesWithFrictionAndMovingObstacles) {
  // A handful of free vertices near each obstacle kind, some penetrating, with friction lagged
  // at a start state and obstacles that move over the step.
  std::vector<std::shared_ptr<const Obstacle>> obstacles;
  std::vector<ContactParameters> params;
  int k = 0;
  for (const auto& shape : all_shapes()) {
    Translation slide{Eigen::Vector3d(0.02 * k, -0.01, 0.01)};
    obstacles.push_back(std::make_shared<Obstacle>(shape->type(), shape, slide));
    params.push_back({1e3 * (1 + k), 0.3 + 0.1 * k});
    ++k;
  }
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.1, 1.1);
  const int n = 40;
  Eigen::VectorXd x_n(3 * n);
  for (Eigen::Index i = 0; i < x_n.size(); ++i) x_n(i) = u(rng);
  std::vector<int> vertices(n);
  for (int v = 0; v < n; ++v) vertices[v] = v;
  Eigen::VectorXd areas = Eigen::VectorXd::Constant(n, 0.02);
  for (bool project : {false, true}) {
    PenaltyContactForm form(obstacles, params, vertices, areas, project);
    form.begin_step(x_n, 3.0, 4.0, 1e-3);
    const Eigen::VectorXd x = perturbed(x_n, 0.01, 8);
    ASSERT_GT(form.stats(x).contacts, 20);
    const auto e = form_derivative_errors(form, x, n, 1e-7);
    EXPECT_LT(e.gradient, 1e-6);
    if (!project) {
      EXPECT_LT(e.hessian, 1e-5);
    }
    EXPECT_LT(e.asymmetry, 1e-12);
    if (project) {
      std::vector<std::vector<int>> cliques;
      for (int v = 0; v < n; ++v) cliques.push_back({v});
      BlockHessian H(n, cliques);
      form.add_hessian(x, H);
      EXPECT_GE(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(Eigen::MatrixXd(H.matrix())).eigenvalues().minCoeff(),
                -1e-9);
    }
  }
}

TEST(PenaltyContact, FrictionForceSaturatesAtMuTimesNormalForce) {
  auto ground = std::make_shared<Obstacle>("ground", std::make_shared<PlaneObstacle>(Eigen::Vector3d::Zero(),
                                                                                    Eigen::Vector3d::UnitZ()));
  PenaltyContactForm form({ground}, {{1e4, 0.5}}, {0}, Eigen::VectorXd::Constant(1, 0.1));
  const Eigen::VectorXd x_n = Eigen::Vector3d(0, 0, -0.01);
  form.begin_step(x_n, 0.0, 1.0, 1e-4);
  const double normal = 0.1 * 1e4 * 0.01;
  for (double slide : {1e-3, 1e-2, 1.0}) {
    Eigen::VectorXd g = Eigen::VectorXd::Zero(3);
    form.add_gradient(Eigen::Vector3d(slide, 0, -0.01), g);
    EXPECT_NEAR(g(0), 0.5 * normal, 1e-12);           // kinetic friction, opposing the slide
    EXPECT_NEAR(g(2), -normal, 1e-12);                // the penalty pushes out of the ground
  }
  Eigen::VectorXd g = Eigen::VectorXd::Zero(3);
  form.add_gradient(Eigen::Vector3d(0.5e-4, 0, -0.01), g);
  EXPECT_GT(g(0), 0.0);
  EXPECT_LT(g(0), 0.5 * normal);  // below the slip threshold: a stiff spring
}

}  // namespace
}  // namespace sinew
