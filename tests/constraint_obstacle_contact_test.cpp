// Constraint contact (paper 001 §5) against rigid obstacles: no penetration beyond the
// tolerance on a static sphere and a moving box, Coulomb stick/slip on an inclined plane.
#include <gtest/gtest.h>

#include <cmath>

#include "sinew/forms/corotational_hex_form.hpp"
#include "sinew/constraints/obstacle_contacts.hpp"
#include "experiments/paper001_experiments.hpp"
#include "sinew/element/mass.hpp"
#include "sinew/mesh/lattice.hpp"
#include "sinew/mesh/surface.hpp"

namespace sinew {
namespace {

constexpr double kGravity = 9.81;

struct Body {
  std::shared_ptr<CorotationalHexForm> model;
  Eigen::VectorXd masses, gravity;
  std::vector<int> surface;
};

Body make_body(const VolumeMesh& mesh, double young, double density, const Eigen::Vector3d& g) {
  Body b;
  b.model = std::make_shared<CorotationalHexForm>(std::make_shared<Discretization>(mesh),
                                              HookeCoefficients::from_young_poisson(young, 0.3));
  b.masses = lumped_mass(b.model->discretization(), density);
  b.gravity = Eigen::VectorXd::Zero(3 * mesh.num_vertices());
  for (Eigen::Index v = 0; v < mesh.num_vertices(); ++v) b.gravity.segment<3>(3 * v) = g * b.masses(v);
  b.surface = boundary_surface(mesh).vertices;
  return b;
}

// The deepest penetration of the body's vertices into the obstacle at `frame`.
double penetration(const Obstacle& o, const Eigen::VectorXd& x, double frame) {
  double deepest = 0.0;
  for (Eigen::Index v = 0; v < x.size() / 3; ++v) deepest = std::max(deepest, -o.query(x.segment<3>(3 * v), frame).distance);
  return deepest;
}

TEST(ConstraintObstacleContact, ProviderReportsGapNormalAndObstacleVelocity) {
  // A box moving up 0.1 m per frame (frames of 0.05 s: 2 m/s); a vertex 0.01 m above its top.
  auto box = std::make_shared<Obstacle>("lift", std::make_shared<BoxObstacle>(Eigen::Vector3d(-1, -1, -1), Eigen::Vector3d(1, 1, 0)),
                                        Translation{Eigen::Vector3d(0, 0, 0.1)});
  const ContactProvider provider = obstacle_contacts({{box, 0.4}}, {0, 1}, 0.05, 0.05);
  Eigen::VectorXd x(6);
  x << 0.2, 0.3, 0.11, 5, 5, 5;  // vertex 1 far away
  // Step [0.05, 0.1] s = frames [1, 2]: the box top is at z = 0.2 at the step's end.
  const std::vector<ContactCandidate> c = provider(x, 0.05, 0.1);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_EQ(c[0].vertex, 0);
  EXPECT_NEAR(c[0].gap, -0.09, 1e-12);
  EXPECT_TRUE(c[0].normal.isApprox(Eigen::Vector3d::UnitZ(), 1e-12));
  EXPECT_DOUBLE_EQ(c[0].friction, 0.4);
  EXPECT_TRUE(c[0].obstacle_velocity.isApprox(Eigen::Vector3d(0, 0, 2.0), 1e-9));
}

TEST(ConstraintObstacleContact, SphereDroppedOnStaticSphereDoesNotPenetrate) {
  // The 27-hex sphere of paper 001 (R = 0.3 m) dropped off-centre onto a fixed sphere (R = 0.5 m).
  const VolumeMesh mesh = paper001::sphere_mesh(Eigen::Vector3d(0.15, 0, 1.1), 0.3, 3);
  const Body b = make_body(mesh, 2e5, 500.0, Eigen::Vector3d(0, 0, -kGravity));
  auto ball = std::make_shared<Obstacle>("ball", std::make_shared<SphereObstacle>(Eigen::Vector3d::Zero(), 0.5));
  EnergyLimitedStepSettings s;
  s.time_step = 0.01;
  const double frame_seconds = 0.01;
  EnergyLimitedStepper stepper(b.model, b.masses, b.gravity, std::vector<char>(b.gravity.size(), 0),
                             obstacle_contacts({{ball, 0.3}}, b.surface, 0.05, frame_seconds), s);
  Eigen::VectorXd x = mesh.rest_positions(), v = Eigen::VectorXd::Zero(x.size());
  int touching_steps = 0;
  for (int k = 0; k < 60; ++k) {
    const EnergyLimitedStepReport r = stepper.step(x, v);
    EXPECT_TRUE(r.converged) << "step " << k;
    EXPECT_LE(penetration(*ball, x, stepper.time() / frame_seconds), s.contact_tolerance) << "step " << k;
    if (r.active_contacts > 0) ++touching_steps;
  }
  EXPECT_GT(touching_steps, 10);  // it did land (free fall reaches the ball after ~0.2 s)
  // Pushed off sideways (+x): the contact normal at an off-centre landing points away from the axis.
  double mean_x = 0.0;
  for (Eigen::Index i = 0; i < mesh.num_vertices(); ++i) mean_x += x(3 * i) / mesh.num_vertices();
  EXPECT_GT(mean_x, 0.15);
}

TEST(ConstraintObstacleContact, BoxDroppedOnRisingBoxDoesNotPenetrate) {
  // A 2 x 2 x 2-hex box falls while a box obstacle rises at 1 m/s towards it and stops at frame
  // 30 (keyframes); the body must end up carried and resting on the obstacle's top.
  const VolumeMesh mesh = box_lattice(Eigen::Vector3d(-0.1, -0.1, 0.5), Eigen::Vector3d(0.1, 0.1, 0.7), Eigen::Vector3i(2, 2, 2));
  const Body b = make_body(mesh, 1e6, 500.0, Eigen::Vector3d(0, 0, -kGravity));
  Keyframes path;
  path.keys = {{0.0, Eigen::Quaterniond::Identity(), Eigen::Vector3d::Zero()},
               {30.0, Eigen::Quaterniond::Identity(), Eigen::Vector3d(0, 0, 0.3)}};
  auto lift = std::make_shared<Obstacle>("lift", std::make_shared<BoxObstacle>(Eigen::Vector3d(-1, -1, -1), Eigen::Vector3d(1, 1, 0)),
                                         path);
  EnergyLimitedStepSettings s;
  s.time_step = 0.01;
  const double frame_seconds = 0.01;
  EnergyLimitedStepper stepper(b.model, b.masses, b.gravity, std::vector<char>(b.gravity.size(), 0),
                             obstacle_contacts({{lift, 0.5}}, b.surface, 0.02, frame_seconds), s);
  Eigen::VectorXd x = mesh.rest_positions(), v = Eigen::VectorXd::Zero(x.size());
  for (int k = 0; k < 60; ++k) {
    const EnergyLimitedStepReport r = stepper.step(x, v);
    EXPECT_TRUE(r.converged) << "step " << k;
    EXPECT_LE(penetration(*lift, x, stepper.time() / frame_seconds), s.contact_tolerance) << "step " << k;
  }
  // Resting on the top (z = 0.3) after the obstacle stopped: lowest vertex at the surface.
  const double lowest = x.reshaped(3, x.size() / 3).row(2).minCoeff();
  EXPECT_NEAR(lowest, 0.3, 2e-3);
}

// A stiff block on a plane tilted by theta about y; returns its down-slope travel after `seconds`.
double slope_travel(double theta, double mu, double seconds) {
  const Eigen::Vector3d normal(std::sin(theta), 0.0, std::cos(theta));
  const Eigen::Vector3d down_slope(std::cos(theta), 0.0, -std::sin(theta));
  // Built in the slope's frame: local x down the slope, local z along the normal, resting on it.
  VolumeMesh mesh = box_lattice(Eigen::Vector3d(0, -0.05, 0), Eigen::Vector3d(0.1, 0.05, 0.1), Eigen::Vector3i(1, 1, 1));
  for (Eigen::Index v = 0; v < mesh.num_vertices(); ++v) {
    const Eigen::Vector3d p = mesh.vertices.row(v).transpose();
    mesh.vertices.row(v) = (p.x() * down_slope + p.y() * Eigen::Vector3d::UnitY() + p.z() * normal).transpose();
  }
  const Body b = make_body(mesh, 1e7, 1000.0, Eigen::Vector3d(0, 0, -kGravity));
  auto plane = std::make_shared<Obstacle>("slope", std::make_shared<PlaneObstacle>(Eigen::Vector3d::Zero(), normal));
  EnergyLimitedStepSettings s;
  s.time_step = 0.01;
  EnergyLimitedStepper stepper(b.model, b.masses, b.gravity, std::vector<char>(b.gravity.size(), 0),
                             obstacle_contacts({{plane, mu}}, b.surface, 0.01, 0.01), s);
  Eigen::VectorXd x = mesh.rest_positions(), v = Eigen::VectorXd::Zero(x.size());
  const Eigen::VectorXd x0 = x;
  for (int k = 0; k < static_cast<int>(std::lround(seconds / s.time_step)); ++k) {
    const EnergyLimitedStepReport r = stepper.step(x, v);
    EXPECT_TRUE(r.converged);
    EXPECT_LE(penetration(*plane, x, 0.0), s.contact_tolerance);
  }
  double travel = 0.0;
  for (Eigen::Index i = 0; i < mesh.num_vertices(); ++i) travel += down_slope.dot((x - x0).segment<3>(3 * i)) / mesh.num_vertices();
  return travel;
}

TEST(ConstraintObstacleContact, FrictionOnInclinedPlaneSticksOrSlidesPerMu) {
  const double theta = 20.0 * M_PI / 180.0, seconds = 0.5;  // tan(20 deg) = 0.364
  // mu = 0.5 > tan(theta): sticks (only the elastic settling moves it, well under a millimetre).
  EXPECT_LT(std::abs(slope_travel(theta, 0.5, seconds)), 1e-3);
  // mu = 0.1 and frictionless: slides with a = g (sin theta - mu cos theta), travel a t^2 / 2
  // (backward Euler's first-order lag is a few per cent at h = 0.01 s over 50 steps).
  for (double mu : {0.1, 0.0}) {
    const double expected = 0.5 * kGravity * (std::sin(theta) - mu * std::cos(theta)) * seconds * seconds;
    EXPECT_NEAR(slope_travel(theta, mu, seconds), expected, 0.05 * expected) << "mu = " << mu;
  }
}

}  // namespace
}  // namespace sinew
