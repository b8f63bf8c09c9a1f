// Time stepping: backward Euler's energy behaviour, a block and a ball resting on the ground at
// the penalty equilibrium, and Coulomb friction on a slope (stick below tan(theta), slide
// above it with the analytic acceleration).
#include <gtest/gtest.h>

#include <cmath>

#include "sinew/forms/penalty_contact_form.hpp"
#include "sinew/forms/elastic_form.hpp"
#include "sinew/forms/external_force_form.hpp"
#include "sinew/material/families/stable_neo_hookean.hpp"
#include "sinew/mesh/lattice.hpp"
#include "sinew/integrator/time_stepper.hpp"

namespace sinew {
namespace {

constexpr double kDensity = 1000.0;

// A block with its forms; the caller adds gravity and obstacles, then builds the stepper.
struct Block {
  std::shared_ptr<Discretization> disc;
  std::shared_ptr<ElasticForm> elastic;
  std::shared_ptr<MassMatrix> mass;
  std::shared_ptr<InertiaForm> inertia;
  std::shared_ptr<PenaltyContactForm> contact;
  std::unique_ptr<Problem> problem;
  std::unique_ptr<TimeStepper> stepper;
  std::unique_ptr<LinearSolver> linear = make_linear_solver({});
  Eigen::VectorXd x, v, gravity;

  Block(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, int cells, double E, double nu, double h, MassKind kind)
      : Block(box_lattice(lo, hi, Eigen::Vector3i::Constant(cells)), E, nu, h, kind) {}
  Block(VolumeMesh mesh, double E, double nu, double h, MassKind kind) {
    disc = std::make_shared<Discretization>(std::move(mesh));
    const double mu = E / (2 * (1 + nu)), lambda = E * nu / ((1 + nu) * (1 - 2 * nu));
    elastic = std::make_shared<ElasticForm>(disc, std::make_shared<StableNeoHookean>(lambda, mu));
    mass = std::make_shared<MassMatrix>(*disc, kDensity, kind);
    inertia = std::make_shared<InertiaForm>(mass, h);
    problem = std::make_unique<Problem>(disc->mesh().num_vertices());
    problem->add_form(elastic);
    problem->add_form(inertia);
    x = disc->mesh().rest_positions();
    v = Eigen::VectorXd::Zero(x.size());
    gravity = Eigen::VectorXd::Zero(x.size());
  }
  void add_gravity(const Eigen::Vector3d& g) {
    gravity = gravity_forces(mass->lumped(), g);
    problem->add_form(std::make_shared<ExternalForceForm>(gravity));
  }
  void add_ground(double stiffness, double friction) {
    const BoundarySurface surface = boundary_surface(disc->mesh());
    auto ground = std::make_shared<Obstacle>(
        "ground", std::make_shared<PlaneObstacle>(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ()));
    contact = std::make_shared<PenaltyContactForm>(std::vector<std::shared_ptr<const Obstacle>>{ground},
                                                   std::vector<ContactParameters>{{stiffness, friction}},
                                                   surface.vertices, boundary_vertex_areas(disc->mesh(), surface));
    problem->add_form(contact);
  }
  void make_stepper(double tolerance, double friction_velocity = 1e-2) {
    TimeStepSettings s;
    s.newton.test = ConvergenceTest::Absolute;
    s.newton.absolute_tolerance = tolerance;
    s.friction_velocity = friction_velocity;
    stepper = std::make_unique<TimeStepper>(*problem, inertia, nullptr, contact, std::vector<KinematicCondition>{},
                                            disc->mesh().vertices, s);
  }
  void step(int n) {
    const StepStats r = stepper->step(x, v, n, n + 1, *linear);
    ASSERT_TRUE(r.converged) << r.failure;
  }
  Eigen::Vector3d mean_displacement() const {
    return (x - disc->mesh().rest_positions()).reshaped(3, x.size() / 3).rowwise().mean();
  }
};

TEST(BackwardEuler, ReleasedPrestretchedBlockLosesEnergyMonotonically) {
  for (MassKind kind : {MassKind::Lumped, MassKind::Consistent}) {
    Block b(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), 2, 1e4, 0.3, 0.01, kind);
    b.make_stepper(1e-8);
    // Stretched by 20 % along x, released at rest: no gravity, no damping, no contact.
    for (Eigen::Index i = 0; i < b.x.size(); i += 3) b.x(i) *= 1.2;
    auto total = [&] { return b.elastic->value(b.x) + b.mass->kinetic_energy(b.v); };
    const double e0 = total();
    double previous = e0, max_kinetic = 0.0;
    for (int n = 0; n < 100; ++n) {
      b.step(n);
      const double e = total();
      EXPECT_LE(e, previous * (1 + 1e-10)) << "step " << n;  // backward Euler never adds energy
      previous = e;
      max_kinetic = std::max(max_kinetic, b.mass->kinetic_energy(b.v));
    }
    EXPECT_GT(max_kinetic, 0.3 * e0);   // it did oscillate ...
    EXPECT_LT(previous, 0.5 * e0);      // ... and its numerical damping took most of the energy
    EXPECT_GT(previous, 1e-3 * e0);
    // Momentum stays zero (no external force).
    EXPECT_LT(b.mass->apply(b.v).reshaped(3, b.v.size() / 3).rowwise().sum().norm(), 1e-8);
  }
}

TEST(PenaltyContactDynamics, BlockComesToRestAtPenaltyEquilibriumDepth) {
  // A stiff block falls 5 mm onto the ground and settles where the penalty carries its weight:
  // depth = m g / (k * sum of the contact vertices' areas).
  Block b(Eigen::Vector3d(0, 0, 0.005), Eigen::Vector3d(0.2, 0.2, 0.205), 2, 1e8, 0.3, 0.005, MassKind::Lumped);
  b.add_gravity(Eigen::Vector3d(0, 0, -9.81));
  const double k = 1e6;
  b.add_ground(k, 0.0);
  b.make_stepper(1e-6);
  for (int n = 0; n < 300; ++n) b.step(n);
  const BoundarySurface surface = boundary_surface(b.disc->mesh());
  const Eigen::VectorXd areas = boundary_vertex_areas(b.disc->mesh(), surface);
  double bottom_area = 0.0, depth = 0.0;
  int bottom = 0;
  for (Eigen::Index v = 0; v < b.disc->mesh().num_vertices(); ++v)
    if (b.disc->mesh().vertices(v, 2) < 0.006) {
      bottom_area += areas(v);
      depth += -b.x(3 * v + 2);
      ++bottom;
    }
  depth /= bottom;
  const double weight = b.mass->lumped().sum() * 9.81;
  const double expected = weight / (k * bottom_area);
  EXPECT_NEAR(depth, expected, 0.02 * expected);
  EXPECT_LT(b.mass->kinetic_energy(b.v), 1e-6 * weight * expected);  // at rest
  EXPECT_EQ(b.contact->stats(b.x).contacts, bottom);
}

TEST(PenaltyContactDynamics, BallComesToRestWherePenaltyForcesCarryItsWeight) {
  // A ball (a tet-split sphere lattice) dropped from 2 cm settles: at rest the penalty forces
  // sum_v a_v k max(0, -z_v) of its penetrating vertices carry exactly its weight.
  const Eigen::Vector3d c(0, 0, 0.12);
  const SignedDistance sphere = sphere_sdf(c, 0.1);
  VolumeMesh mesh = tetrahedralize_hexes(occupancy_lattice(Eigen::AlignedBox3d(c.array() - 0.1, c.array() + 0.1),
                                                           Eigen::Vector3i::Constant(4),
                                                           [&](const Eigen::Vector3d& p) { return sphere(p) <= 0.0; }));
  Block b(std::move(mesh), 1e6, 0.4, 0.01, MassKind::Lumped);
  b.add_gravity(Eigen::Vector3d(0, 0, -9.81));
  const double k = 1e6;
  b.add_ground(k, 0.0);
  b.make_stepper(1e-6);
  for (int n = 0; n < 150; ++n) b.step(n);
  const BoundarySurface surface = boundary_surface(b.disc->mesh());
  const Eigen::VectorXd areas = boundary_vertex_areas(b.disc->mesh(), surface);
  double support = 0.0;
  for (int v : surface.vertices) support += areas(v) * k * std::max(0.0, -b.x(3 * v + 2));
  const double weight = b.mass->lumped().sum() * 9.81;
  EXPECT_NEAR(support, weight, 0.01 * weight);
  EXPECT_GT(b.contact->stats(b.x).contacts, 0);
  EXPECT_LT(b.mass->kinetic_energy(b.v), 1e-4 * weight * 0.01);
}

// Slides a block down a slope of angle theta (gravity tilted) for 0.5 s; returns the distance.
double slide_distance(double mu, double theta) {
  // Starts slightly inside the ground, near the penalty equilibrium depth, so that friction's
  // lagged normal force acts from the first step.
  Block b(Eigen::Vector3d(0, 0, -1e-4), Eigen::Vector3d(0.2, 0.2, 0.2), 2, 1e7, 0.3, 0.01, MassKind::Lumped);
  b.add_gravity(9.81 * Eigen::Vector3d(std::sin(theta), 0, -std::cos(theta)));
  b.add_ground(1e7, mu);
  b.make_stepper(1e-6, 1e-3);
  for (int n = 0; n < 50; ++n) b.step(n);
  return b.mean_displacement()(0);
}

TEST(PenaltyContactDynamics, FrictionSticksAboveTanThetaAndSlidesBelow) {
  const double theta = std::atan(0.5), g = 9.81, t = 0.5;
  EXPECT_LT(std::abs(slide_distance(0.8, theta)), 1e-3);
  const double mu = 0.3;
  const double expected = 0.5 * g * (std::sin(theta) - mu * std::cos(theta)) * t * t;
  EXPECT_NEAR(slide_distance(mu, theta), expected, 0.1 * expected);
  EXPECT_NEAR(slide_distance(0.0, theta), 0.5 * g * std::sin(theta) * t * t, 0.1 * 0.5 * g * std::sin(theta) * t * t);
}

}  // namespace
}  // namespace sinew
