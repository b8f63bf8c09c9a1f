// Reference-map penalty self-contact (paper 000 §6): closest points, the form's derivatives with
// the targets frozen, detection, and two blocks pushed into each other.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <random>

#include "dynamics_test_support.hpp"
#include "sinew/forms/self_contact_form.hpp"
#include "sinew/core/error.hpp"
#include "sinew/element/discretization.hpp"
#include "sinew/forms/elastic_form.hpp"
#include "sinew/material/spec.hpp"
#include "sinew/mesh/lattice.hpp"
#include "sinew/solver/newton.hpp"
#include "sinew/integrator/time_stepper.hpp"

namespace sinew {
namespace {

// Two unit-width blocks side by side along x with a gap, as one mesh.
VolumeMesh two_blocks(double gap, int cells) {
  const VolumeMesh a = box_lattice(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1), Eigen::Vector3i::Constant(cells));
  const VolumeMesh b = box_lattice(Eigen::Vector3d(1 + gap, 0, 0), Eigen::Vector3d(2 + gap, 1, 1), Eigen::Vector3i::Constant(cells));
  VolumeMesh m;
  m.vertices.resize(a.num_vertices() + b.num_vertices(), 3);
  m.vertices << a.vertices, b.vertices;
  m.elements.resize(a.num_elements() + b.num_elements(), 8);
  m.elements << a.elements, (b.elements.array() + static_cast<int>(a.num_vertices())).matrix();
  return m;
}

// Block b's vertices come second (same count as a's).
bool in_b(const VolumeMesh& m, Eigen::Index v) { return v >= m.num_vertices() / 2; }

// Moves block b by dx along x.
Eigen::VectorXd shifted(const VolumeMesh& m, double dx) {
  Eigen::VectorXd x = m.rest_positions();
  for (Eigen::Index v = 0; v < m.num_vertices(); ++v)
    if (in_b(m, v)) x(3 * v) += dx;
  return x;
}

TEST(SelfContactGeometry, ClosestPointMatchesDenseSampling) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 50; ++trial) {
    const Eigen::Vector3d a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng)), c(u(rng), u(rng), u(rng));
    const Eigen::Vector3d p = 2.0 * Eigen::Vector3d(u(rng), u(rng), u(rng));
    const Eigen::Vector3d w = closest_point_barycentric(p, a, b, c);
    EXPECT_NEAR(w.sum(), 1.0, 1e-12);
    EXPECT_GE(w.minCoeff(), -1e-12);
    const double d = (w(0) * a + w(1) * b + w(2) * c - p).norm();
    double best = 1e9;
    const int n = 200;
    for (int i = 0; i <= n; ++i)
      for (int j = 0; i + j <= n; ++j) {
        const double s = double(i) / n, t = double(j) / n;
        best = std::min(best, ((1 - s - t) * a + s * b + t * c - p).norm());
      }
    EXPECT_LE(d, best + 1e-12);
    EXPECT_GE(d, best - 0.02);  // the sampling's resolution
  }
}

TEST(SelfContactDetection, NoContactAtRestAndInTouchingBlocks) {
  const VolumeMesh m = two_blocks(0.0, 3);  // touching faces, no shared vertices
  const SelfContactForm form(m, SelfContactSettings{});
  EXPECT_TRUE(form.detect(m.rest_positions()).empty());
  EXPECT_TRUE(form.detect(shifted(m, 0.05)).empty());
}

TEST(SelfContactDetection, PenetratingSamplesGetTargetsOnTheOtherBlocksSurface) {
  const VolumeMesh m = two_blocks(0.0, 3);
  SelfContactSettings s;
  const SelfContactForm form(m, s);
  const double overlap = 0.1;
  const std::vector<SurfaceContact> contacts = form.detect(shifted(m, -overlap));
  ASSERT_FALSE(contacts.empty());
  const Eigen::VectorXd x = shifted(m, -overlap);
  for (const auto& c : contacts) {
    const Eigen::Vector3d xs = x.segment<3>(3 * c.sample);
    // Interior samples of the touching faces are 0.1 deep; the target lies on the other block's
    // face x = 1 (for a sample of b) or x = 1 - overlap (for a sample of a).
    const bool of_a = !in_b(m, c.sample);
    EXPECT_NEAR(c.target.x(), of_a ? 1.0 - overlap : 1.0, 1e-12) << c.sample;
    EXPECT_NEAR(c.depth, (xs - c.target).norm(), 1e-14);
    EXPECT_LE(c.depth, overlap + 1e-12);
  }
}

// add_at_iterate (after each accepted Newton step): nothing before the first contact (a solve's
// first iterates are distorted near the bones); once contacts exist, newly penetrating samples are
// added and the known ones keep their triangle, weights and normal; samples that left the body
// are not dropped (only refresh drops, at converged states).
TEST(SelfContactForm, AddsSamplesAtIteratesOnlyOnceContactsExist) {
  const VolumeMesh m = two_blocks(0.0, 3);
  SelfContactForm form(m, SelfContactSettings{});
  const Eigen::VectorXd full = shifted(m, -0.05);
  // Only the lower half of block b (rest y < 0.5) pushed into a.
  Eigen::VectorXd partial = m.rest_positions();
  for (Eigen::Index v = 0; v < m.num_vertices(); ++v)
    if (in_b(m, v) && m.vertices(v, 1) < 0.5) partial(3 * v) -= 0.05;
  EXPECT_FALSE(form.add_at_iterate(full));
  EXPECT_TRUE(form.contacts().empty());
  ASSERT_TRUE(form.refresh(partial));
  const std::vector<SurfaceContact> first = form.contacts();
  ASSERT_FALSE(first.empty());
  const size_t all = form.detect(full).size();
  ASSERT_GT(all, first.size());
  EXPECT_TRUE(form.add_at_iterate(full));
  EXPECT_TRUE(form.couplings_changed());
  EXPECT_EQ(form.contacts().size(), all);
  for (const SurfaceContact& c : first) {
    const auto it = std::find_if(form.contacts().begin(), form.contacts().end(),
                                 [&](const SurfaceContact& k) { return k.sample == c.sample; });
    ASSERT_NE(it, form.contacts().end()) << c.sample;
    EXPECT_EQ(it->triangle, c.triangle);
    EXPECT_EQ(it->weights, c.weights);
    EXPECT_EQ(it->normal, c.normal);
  }
  EXPECT_FALSE(form.add_at_iterate(full));  // nothing new
  EXPECT_FALSE(form.couplings_changed());
  EXPECT_FALSE(form.add_at_iterate(m.rest_positions()));  // all outside: none dropped here
  EXPECT_EQ(form.contacts().size(), all);

  // Samples deep inside at an iterate wait for the converged state (refresh adds them).
  SelfContactForm deep(m, SelfContactSettings{});
  ASSERT_TRUE(deep.refresh(partial));
  const size_t before = deep.contacts().size();
  const Eigen::VectorXd far = shifted(m, -0.4);
  deep.add_at_iterate(far);
  EXPECT_LT(deep.contacts().size(), deep.detect(far).size());
  for (const SurfaceContact& c : deep.contacts()) EXPECT_LE(c.depth, 0.4 - 0.05) << c.sample;  // none 0.4 deep added
  EXPECT_GE(deep.contacts().size(), before);
  EXPECT_TRUE(deep.refresh(far));
  EXPECT_GE(deep.contacts().size(), deep.detect(far).size());
}

// surface_depth: how far a penetrating sample is from the nearest deformed surface outside its
// own neighbourhood. Block b pushed 0.1 into block a: the samples of a's face x = 1 away from
// b's edges are exactly 0.1 inside b (its face x = 0.9); none is deeper than the overlap.
TEST(SelfContactDetection, SurfaceDepthIsTheDistanceToTheOtherBlocksFace) {
  const VolumeMesh m = two_blocks(0.0, 3);
  const SelfContactForm form(m, SelfContactSettings{});
  const double overlap = 0.1;
  const Eigen::VectorXd x = shifted(m, -overlap);
  const std::vector<SurfaceContact> contacts = form.detect(x);
  ASSERT_FALSE(contacts.empty());
  int interior = 0;
  for (const auto& c : contacts) {
    const double d = form.surface_depth(x, c.sample);
    EXPECT_LE(d, overlap + 1e-12) << c.sample;
    EXPECT_GE(d, 0.0) << c.sample;
    const Eigen::Vector3d X = m.vertices.row(c.sample).transpose();
    if (!in_b(m, c.sample) && X.y() > 0.2 && X.y() < 0.8 && X.z() > 0.2 && X.z() < 0.8) {
      EXPECT_NEAR(d, overlap, 1e-12) << c.sample;
      ++interior;
    }
  }
  EXPECT_GT(interior, 0);
  EXPECT_THROW(form.surface_depth(x, -1), Error);
}

TEST(SelfContactForm, GradientAndHessianMatchFiniteDifferencesWithTargetsFrozen) {
  const VolumeMesh m = two_blocks(0.0, 2);
  SelfContactSettings s;
  s.stiffness = 3e3;
  s.refine = true;
  SelfContactForm form(m, s);
  Eigen::VectorXd x = shifted(m, -0.2);
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> u(-0.03, 0.03);
  for (Eigen::Index i = 0; i < x.size(); ++i) x(i) += u(rng);
  ASSERT_TRUE(form.refresh(x));
  ASSERT_FALSE(form.contacts().empty());
  Eigen::VectorXd g = Eigen::VectorXd::Zero(x.size());
  form.add_gradient(x, g);
  std::vector<std::vector<int>> cliques;
  form.couplings(cliques);
  BlockHessian H(m.num_vertices(), cliques);
  form.add_hessian(x, H);
  const Eigen::MatrixXd K(H.matrix());
  ASSERT_GT(g.norm(), 0.0);
  testing_support::expect_derivatives_match_per_entry(form, x, g, K);
  // PSD: k A_s I blocks.
  EXPECT_GE(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(K).eigenvalues().minCoeff(), -1e-12 * K.norm());
}

TEST(SelfContactForm, RefinedTargetIsNoFartherThanTheReferenceMapTarget) {
  const VolumeMesh m = two_blocks(0.0, 3);
  Eigen::VectorXd x = shifted(m, -0.15);
  // Shear block b so that the reference map's target is not the deformed closest point.
  for (Eigen::Index v = 0; v < m.num_vertices(); ++v)
    if (in_b(m, v)) x(3 * v + 1) += 0.2 * (m.vertices(v, 0) - 1.0) + 0.1 * m.vertices(v, 2);
  SelfContactSettings plain, refined;
  refined.refine = true;
  const auto a = SelfContactForm(m, plain).detect(x), b = SelfContactForm(m, refined).detect(x);
  ASSERT_FALSE(a.empty());
  double total_a = 0.0, total_b = 0.0;
  int common = 0;
  for (const auto& ca : a)
    for (const auto& cb : b)
      if (ca.sample == cb.sample) {
        EXPECT_LE(cb.depth, ca.depth + 1e-12) << ca.sample;
        total_a += ca.depth;
        total_b += cb.depth;
        ++common;
      }
  ASSERT_GT(common, 0);
  EXPECT_LT(total_b, total_a);  // the shear makes some reference-map targets sub-optimal
}

// Block a's left face is pinned, block b's right face is pushed left by 0.3: without contact
// the blocks overlap by the full 0.3 (they do not interact); with contact the penalty keeps them
// apart up to a small penalty depth and both blocks compress.
TEST(SelfContactSolve, PenaltySeparatesTwoBlocksPushedIntoEachOther) {
  const VolumeMesh m = two_blocks(0.02, 3);
  auto disc = std::make_shared<Discretization>(m, "two blocks");
  MaterialSpec mat;
  mat.family = "stable_neo_hookean";
  mat.target = YoungPoisson{1e4, 0.3};
  std::vector<char> fixed(3 * m.num_vertices(), 0);
  Eigen::VectorXd x0 = m.rest_positions();
  for (Eigen::Index v = 0; v < m.num_vertices(); ++v) {
    const double X = m.vertices(v, 0);
    if (X < 1e-9 || X > 2.02 - 1e-9)
      for (int i = 0; i < 3; ++i) fixed[3 * v + i] = 1;
    if (X > 2.02 - 1e-9) x0(3 * v) -= 0.3;
  }
  auto solve = [&](bool contact, bool refine, SelfContactForm* probe) {
    Problem problem(m.num_vertices());
    problem.add_form(std::make_shared<ElasticForm>(disc, build_material(mat)));
    SelfContactSettings s;
    s.stiffness = 1e6;
    s.refine = refine;
    if (contact) problem.add_form(std::make_shared<SelfContactForm>(m, s));
    problem.set_fixed(fixed);
    auto linear = make_linear_solver(LinearSolverSettings{});
    NewtonSettings ns;  // paper 000's absolute force tolerance 1e-2 (forces here ~1e2-1e3 N)
    ns.test = ConvergenceTest::Absolute;
    Eigen::VectorXd x = x0;
    // Push in six steps so that the first contact is found before the blocks cross.
    for (int step = 1; step <= 6; ++step) {
      Eigen::VectorXd xs = x;
      for (Eigen::Index v = 0; v < m.num_vertices(); ++v)
        if (m.vertices(v, 0) > 2.02 - 1e-9) xs(3 * v) = m.vertices(v, 0) - 0.05 * step;
      const NewtonReport r = newton_solve(problem, xs, *linear, ns, [&](const NewtonIterate& it) {
        if (std::getenv("SINEW_DEBUG_CONTACT"))
          std::printf("step %d it %d residual %.3e energy %.6e alpha %.3g contacts %zu\n", step, it.iteration, it.residual, it.energy, it.step,
                      contact ? static_cast<const SelfContactForm&>(*problem.forms()[1]).contacts().size() : 0);
      });
      // Every step converges to the absolute force tolerance, with contact too: contacts are
      // re-fitted only at the start of each solve and only added within it, so Newton
      // minimises one fixed energy (it stalled near 1e1 N when they were re-fitted every
      // iteration).
      EXPECT_TRUE(r.converged) << "step " << step << ": " << r.failure;
      EXPECT_LT(r.residual, ns.absolute_tolerance) << "step " << step;
      if (contact) std::printf("  contact step %d: %d Newton iterations, residual %.2e\n", step, r.iterations, r.residual);
      x = xs;
    }
    // Overlap along x of the facing faces (mean x of a's face at rest x = 1 minus mean x of b's
    // face at rest x = 1.02).
    double a_face = 0.0, b_face = 0.0;
    int na = 0, nb = 0;
    for (Eigen::Index v = 0; v < m.num_vertices(); ++v) {
      if (std::abs(m.vertices(v, 0) - 1.0) < 1e-9) a_face += x(3 * v), ++na;
      if (std::abs(m.vertices(v, 0) - 1.02) < 1e-9) b_face += x(3 * v), ++nb;
    }
    (void)probe;
    return a_face / na - b_face / nb;
  };
  SelfContactForm probe(m, SelfContactSettings{});
  const double free_overlap = solve(false, false, &probe);
  const double contact_overlap = solve(true, false, &probe);
  std::printf("two blocks pushed 0.3 into each other: face overlap %.4f without contact, %.4f with\n", free_overlap,
              contact_overlap);
  EXPECT_NEAR(free_overlap, 0.28, 1e-6);  // 0.3 push - 0.02 gap: block b passes into a rigidly
  // Penalty depth: the push's force over k A, about 0.01 here (measured below), plus the faces'
  // edges bulging into each other.
  EXPECT_LT(contact_overlap, 0.025);  // measured 0.019
}

// Dynamic solves: block b flies into block a (both free, no gravity). Without contact it
// passes through; with contact each backward-Euler step converges and the blocks bounce off
// each other with the overlap held at the penalty depth.
TEST(SelfContactSolve, TimeSteppedBlocksCollideWithoutPassingThrough) {
  const VolumeMesh m = two_blocks(0.05, 2);
  auto disc = std::make_shared<Discretization>(m, "two blocks");
  MaterialSpec mat;
  mat.family = "stable_neo_hookean";
  mat.target = YoungPoisson{1e4, 0.3};
  const SelfContactForm probe(m, SelfContactSettings{});
  auto run = [&](bool contact) {
    Problem problem(m.num_vertices());
    problem.add_form(std::make_shared<ElasticForm>(disc, build_material(mat)));
    auto mass = std::make_shared<MassMatrix>(*disc, 100.0, MassKind::Lumped);
    auto inertia = std::make_shared<InertiaForm>(mass, 0.01);
    problem.add_form(inertia);
    SelfContactSettings s;
    s.stiffness = 1e6;
    if (contact) problem.add_form(std::make_shared<SelfContactForm>(m, s));
    problem.set_fixed(std::vector<char>(3 * m.num_vertices(), 0));
    TimeStepper stepper(problem, inertia, nullptr, nullptr, {}, m.vertices, TimeStepSettings{});
    auto linear = make_linear_solver(LinearSolverSettings{});
    Eigen::VectorXd x = m.rest_positions(), v = Eigen::VectorXd::Zero(x.size());
    for (Eigen::Index i = 0; i < m.num_vertices(); ++i)
      if (in_b(m, i)) v(3 * i) = -1.0;  // the 0.05 m gap closes after 5 steps
    double worst_overlap = 0.0;
    for (int step = 1; step <= 20; ++step) {
      const StepStats r = stepper.step(x, v, step - 1, step, *linear);
      EXPECT_TRUE(r.converged) << (contact ? "contact" : "free") << " step " << step << ": " << r.failure;
      if (!r.converged) break;
      // Interpenetration: the deepest sample inside the other block (detection at x).
      double depth = 0.0;
      for (const SurfaceContact& c : probe.detect(x)) depth = std::max(depth, c.depth);
      worst_overlap = std::max(worst_overlap, depth);
      if (std::getenv("SINEW_DEBUG_CONTACT"))
        std::printf("%s step %d: depth %.4f, %d Newton\n", contact ? "contact" : "free", step, depth, r.newton_iterations);
    }
    return std::make_pair(worst_overlap, v);
  };
  const auto [free_overlap, free_v] = run(false);
  const auto [contact_overlap, contact_v] = run(true);
  std::printf("time-stepped blocks at 1 m/s: deepest penetration %.4f m free, %.4f m with contact\n", free_overlap,
              contact_overlap);
  EXPECT_GT(free_overlap, 0.1);  // passes through (0.2 - 0.05)
  EXPECT_LT(contact_overlap, 0.005);  // measured 0.0006
  // With contact, block b ends moving away from a or at rest relative to it.
  double va = 0.0, vb = 0.0;
  for (Eigen::Index i = 0; i < m.num_vertices(); ++i) (in_b(m, i) ? vb : va) += contact_v(3 * i);
  EXPECT_GE(vb - va, -1e-6 * m.num_vertices());
}

}  // namespace
}  // namespace sinew

namespace sinew {
namespace {

// No false positives: a curved lattice (a cylinder) at rest and rigidly moved has no contact.
TEST(SelfContactDetection, NoContactOnARestingOrRigidlyMovedCylinder) {
  const SignedDistance sdf = cylinder_sdf(Eigen::Vector3d::Zero(), 0.042, 0.3, 0);
  const VolumeMesh m = occupancy_lattice(Eigen::AlignedBox3d(Eigen::Vector3d(-0.15, -0.042, -0.042), Eigen::Vector3d(0.15, 0.042, 0.042)),
                                         Eigen::Vector3i(30, 8, 8), [&](const Eigen::Vector3d& p) { return sdf(p) <= 0.0; });
  const SelfContactForm form(m, SelfContactSettings{});
  Eigen::VectorXd x = m.rest_positions();
  EXPECT_EQ(form.detect(x).size(), 0u);
  const Mat3 R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  for (Eigen::Index v = 0; v < m.num_vertices(); ++v) x.segment<3>(3 * v) = R * x.segment<3>(3 * v) + Eigen::Vector3d(1, 2, 3);
  EXPECT_EQ(form.detect(x).size(), 0u);
}

}  // namespace
}  // namespace sinew
