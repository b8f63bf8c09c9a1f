// Paper 000 §6's quasistatic experiments at default-suite sizes: the cylinder stretch (Fig. 5-6),
// the cube twist (Fig. 9) and the vertex scramble (Fig. 3). Each test prints our figures beside
// the paper's; the assertions are the properties that hold robustly at these sizes, not the
// paper's exact numbers (its E and mesh layout are unknown, see docs/experiments.md). The
// full-size stretch lives in tests/slow/ (label `slow`).
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fmt/format.h>
#include <filesystem>
#include <functional>

#include "sinew/element/discretization.hpp"
#include "sinew/forms/elastic_form.hpp"
#include "sinew/material/spec.hpp"
#include "sinew/mesh/lattice.hpp"
#include "experiments/paper000_experiments.hpp"

namespace sinew {
namespace {

const std::filesystem::path kExamples = SINEW_EXAMPLES;

// ---- the example scene files describe the same setups as the programmatic builders ----------

void expect_same_scene(const Scene& file, const Scene& built) {
  ASSERT_TRUE(file.mesh.cells.has_value());
  EXPECT_EQ(*file.mesh.cells, *built.mesh.cells);
  EXPECT_EQ(file.mesh.source.index(), built.mesh.source.index());
  EXPECT_EQ(file.material.family, built.material.family);
  ASSERT_TRUE(file.material.target.has_value());
  EXPECT_DOUBLE_EQ(file.material.target->E, built.material.target->E);
  EXPECT_DOUBLE_EQ(file.material.target->nu, built.material.target->nu);
  EXPECT_EQ(file.frames, built.frames);
  EXPECT_DOUBLE_EQ(file.solver.newton.absolute_tolerance, built.solver.newton.absolute_tolerance);
  EXPECT_DOUBLE_EQ(file.solver.newton.linear_tolerance, built.solver.newton.linear_tolerance);
  EXPECT_EQ(file.solver.newton.max_iterations, built.solver.newton.max_iterations);
  EXPECT_EQ(file.solver.linear.kind, built.solver.linear.kind);
  // The boundary motions, compared by where they put each end at the last frame.
  const VolumeMesh a = build_scene_mesh(file), b = build_scene_mesh(built);
  ASSERT_EQ(a.num_vertices(), b.num_vertices());
  EXPECT_EQ(a.elements, b.elements);
  EXPECT_LT((a.vertices - b.vertices).cwiseAbs().maxCoeff(), 1e-12);
  std::vector<KinematicCondition> ka, kb;
  for (const auto& c : file.boundary) ka.push_back({select_vertices(a.vertices, c.select, c.name), c.motion, c.name, {true, true, true}, {}});
  for (const auto& c : built.boundary) kb.push_back({select_vertices(b.vertices, c.select, c.name), c.motion, c.name, {true, true, true}, {}});
  Eigen::VectorXd xa = a.rest_positions(), xb = b.rest_positions();
  std::vector<char> fa(xa.size(), 0), fb(xb.size(), 0);
  apply_kinematics(ka, a.vertices, file.frames, xa, fa);
  apply_kinematics(kb, b.vertices, built.frames, xb, fb);
  EXPECT_EQ(fa, fb);
  EXPECT_LT((xa - xb).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(Experiments, StretchSmallExampleMatchesTheBuilder) {
  StretchConfig c;
  c.diameter_cells = 14;
  c.frames = 12;
  expect_same_scene(load_scene(kExamples / "stretch_medium.json"), stretch_scene(c));
}

TEST(Experiments, TwistExampleMatchesTheBuilder) {
  expect_same_scene(load_scene(kExamples / "twist.json"), twist_scene(TwistConfig{}));
  TwistConfig fixed_corotational;
  fixed_corotational.family = "fixed_corotational";
  expect_same_scene(load_scene(kExamples / "twist_fixed_corotational.json"), twist_scene(fixed_corotational));
}

TEST(Experiments, PaperSizeStretchExampleHasThePapersElementCount) {
  const Scene file = load_scene(kExamples / "stretch.json");
  expect_same_scene(file, stretch_scene(StretchConfig{}));
  const VolumeMesh mesh = build_scene_mesh(file);
  std::printf("stretch lattice 67 x 67 x 87: %ld hexahedra, %ld DOFs (paper: %ld hexahedra, %ld DOFs)\n",
              static_cast<long>(mesh.num_elements()), static_cast<long>(3 * mesh.num_vertices()), kPaperStretchHexes,
              kPaperStretchDofs);
  EXPECT_NEAR(static_cast<double>(mesh.num_elements()), static_cast<double>(kPaperStretchHexes), 1e-3 * kPaperStretchHexes);
  EXPECT_NEAR(static_cast<double>(3 * mesh.num_vertices()), static_cast<double>(kPaperStretchDofs), 1e-3 * kPaperStretchDofs);
}

// The smallest eigenvalue of the unprojected Hessian of the elastic energy at x over the DOFs of
// the vertices that are not pinned: positive at a strict local minimum, negative at a saddle.
double smallest_free_eigenvalue(const VolumeMesh& mesh, const std::string& family, double E, double nu,
                                const Eigen::VectorXd& x, const std::function<bool(Eigen::Index vertex)>& pinned) {
  auto disc = std::make_shared<Discretization>(mesh);
  MaterialSpec m;
  m.family = family;
  m.target = YoungPoisson{E, nu};
  auto form = std::make_shared<ElasticForm>(disc, build_material(m), Projection::None);
  Problem problem(mesh.num_vertices());
  problem.add_form(form);
  const Eigen::MatrixXd H = Eigen::MatrixXd(*problem.hessian(x).matrix());
  std::vector<Eigen::Index> free;
  for (Eigen::Index i = 0; i < H.rows(); ++i)
    if (!pinned(i / 3)) free.push_back(i);
  Eigen::MatrixXd Hf(free.size(), free.size());
  for (size_t a = 0; a < free.size(); ++a)
    for (size_t b = 0; b < free.size(); ++b) Hf(a, b) = H(free[a], free[b]);
  return Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(Hf, Eigen::EigenvaluesOnly).eigenvalues().minCoeff();
}

// ---- stretch ----------------------------------------------------------------------------------

// The stretch on a small cylinder: 12 frames of 0.2 to 3.4x, of which the first `run_frames` run.
ExperimentRun small_stretch(const std::string& family, int diameter_cells, int run_frames = 12) {
  StretchConfig c;
  c.family = family;
  c.diameter_cells = diameter_cells;
  c.frames = 12;
  c.solver = paper_solver(1e-3, 100);
  ExperimentOptions o;
  o.frames = run_frames;
  const ExperimentRun run = run_experiment(stretch_scene(c), o);
  const auto paper = paper_stretch_figure(family);
  std::printf("stretch %-22s %ld hexes to %.1fx: volume %+6.2f %% (paper at 3.4x %+5.1f %%), %d/%zu frames converged, "
              "%d Newton, %d CG, %.1f s\n",
              family.c_str(), static_cast<long>(run.elements), 1.0 + (c.stretch - 1.0) * run_frames / c.frames,
              run.volume_change_percent(), paper ? paper->volume_change_percent : 0.0, run.frames_converged(),
              run.frames.size(), run.total_newton(), run.total_linear(), run.seconds());
  return run;
}

// SNH converges every frame and gains a little volume. Lower bound: a free uniaxial bar of the
// same SNH material at stretch 3.4 has J = 1.0128 (`sinew material curve`); pinning the end
// faces against lateral contraction only adds hydrostatic tension, so the gain is at least
// about that. Upper bound: the paper's +4.3 % plus margin for our coarse mesh; 10 % is what
// nu = 0.49 (bulk modulus 50 times the shear modulus) can hardly exceed without tearing.
TEST(Experiments, StretchStableNeoHookeanConvergesAndNearlyPreservesVolume) {
  const ExperimentRun run = small_stretch("stable_neo_hookean", 14);  // 2,808 hexahedra
  EXPECT_EQ(run.frames_converged(), static_cast<int>(run.frames.size()));
  EXPECT_GT(run.volume_change_percent(), 1.0);
  EXPECT_LT(run.volume_change_percent(), 10.0);
  EXPECT_GT(run.frames.back().min_quadrature_J, 0.0);
}

// The co-rotational volume term tr(S - I) lets the cross-section shrink almost freely: a free bar
// at stretch s has lateral stretch t = (mu - lambda (s - 3)/2) / (mu + lambda), so at nu = 0.49
// (lambda = 49 mu) and s = 2, t = 0.51 and J = s t^2 = 0.52 (-48 %); t passes zero near s = 3.04
// and the cylinder collapses (paper: -83 % at 3.4x). Past about 2.4x our Newton does not
// converge within any affordable cap (docs/experiments.md), so the default test stops at 2x,
// where every frame converges and the loss already exceeds 40 %.
TEST(Experiments, StretchCorotationalLosesMostOfItsVolume) {
  const ExperimentRun run = small_stretch("corotational", 14, 5);
  EXPECT_EQ(run.frames_converged(), 5);
  EXPECT_LT(run.volume_change_percent(), -40.0);
}

// Both keep their volume to a few percent (paper: +4.9 % and +4.5 %); on a coarser cylinder to
// keep the default suite fast. Fixed co-rotational runs to 3.0x only: there the stretched cylinder
// is still a strict minimum (smallest free Hessian eigenvalue ~121), but by 3.2x it is a saddle
// (two lateral modes at ~-430, ~-1,050 at 3.4x), where a descent method slides off slowly and
// whether a solve meets the tolerance first depends on round-off (docs/experiments.md).
TEST(Experiments, StretchFixedCorotationalAndFilteredNeoHookeanKeepVolume) {
  for (const auto& [family, frames] : {std::pair<std::string, int>{"fixed_corotational", 10}, {"neo_hookean_filtered", 12}}) {
    const ExperimentRun run = small_stretch(family, 10, frames);  // 1,040 hexahedra
    EXPECT_EQ(run.frames_converged(), frames) << family;
    EXPECT_GT(run.volume_change_percent(), 0.5) << family;
    EXPECT_LT(run.volume_change_percent(), 10.0) << family;
    if (family != "fixed_corotational") continue;
    StretchConfig c;
    c.family = family;
    c.diameter_cells = 10;
    const VolumeMesh mesh = build_scene_mesh(stretch_scene(c));
    const double z0 = mesh.vertices.col(2).minCoeff(), z1 = mesh.vertices.col(2).maxCoeff();
    const double lambda_min = smallest_free_eigenvalue(mesh, family, c.E, c.nu, run.x, [&](Eigen::Index v) {
      return mesh.vertices(v, 2) <= z0 || mesh.vertices(v, 2) >= z1;  // the end faces move with the grips
    });
    std::printf("stretch %s at 3.0x: smallest free Hessian eigenvalue %.4g\n", family.c_str(), lambda_min);
    EXPECT_GT(lambda_min, 0.0) << family << " at 3.0x is not a strict minimum";
  }
}

// ---- twist ------------------------------------------------------------------------------------

// SNH and fixed co-rotational resolve both quarter turns, each in one solve, without inverting
// any quadrature point.
TEST(Experiments, TwistResolvesBothQuarterTurns) {
  for (const auto& paper : kPaperTwist) {
    TwistConfig c;
    c.family = paper.family;
    const ExperimentRun run = run_experiment(twist_scene(c));
    ASSERT_EQ(run.frames.size(), 2u);
    for (int k = 0; k < 2; ++k) {
      const ExperimentFrame& f = run.frames[k];
      std::printf("twist %-20s %d x pi/2: %d Newton (paper %d), %d CG (paper %d), %s, min J %.3f\n", paper.family, k + 1,
                  f.newton_iterations, paper.newton[k], f.linear_iterations, paper.cg[k],
                  f.converged ? "converged" : f.failure.c_str(), f.min_quadrature_J);
      EXPECT_TRUE(f.converged) << paper.family << " twist " << k + 1 << ": " << f.failure;
      EXPECT_GT(f.min_quadrature_J, 0.0) << paper.family << " twist " << k + 1;
    }
  }
}

// ---- scramble ---------------------------------------------------------------------------------

TEST(Experiments, ScrambleCornersSpanATetrahedron) {
  const VolumeMesh mesh = box_lattice(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), Eigen::Vector3i(3, 3, 3));
  const auto c = tetrahedral_corners(mesh);
  Eigen::Matrix3d edges;
  for (int k = 0; k < 3; ++k) edges.col(k) = (mesh.vertices.row(c[k + 1]) - mesh.vertices.row(c[0])).transpose();
  EXPECT_NEAR(std::abs(edges.determinant()), 2.0, 1e-12);  // edges (1,1,0), (1,0,1), (0,1,1): volume 1/3
  const Eigen::VectorXd x = scramble_positions(mesh, c, 2.0, 7);
  const Eigen::VectorXd rest = mesh.rest_positions();
  for (int v : c) EXPECT_EQ(x.segment<3>(3 * v), rest.segment<3>(3 * v));
  const double half = 0.5 * std::cbrt(2.0);
  EXPECT_LE((x.array() - 0.5).abs().maxCoeff(), half);
  EXPECT_GT((x.array() - 0.5).abs().maxCoeff(), 0.5);  // some vertex leaves the unit cube
  EXPECT_EQ(x, scramble_positions(mesh, c, 2.0, 7));   // deterministic per seed
  EXPECT_NE(x, scramble_positions(mesh, c, 2.0, 8));
}

// The smallest eigenvalue of the unprojected Hessian over the free DOFs at a scramble's final
// state (the four pinned corners removed).
double smallest_free_eigenvalue(const ScrambleConfig& c, const ScrambleResult& r) {
  const VolumeMesh mesh = box_lattice(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), Eigen::Vector3i::Constant(c.cells));
  return smallest_free_eigenvalue(mesh, c.family, c.E, c.nu, r.x, [&](Eigen::Index v) {
    return std::find(r.pinned.begin(), r.pinned.end(), static_cast<int>(v)) != r.pinned.end();
  });
}

// Elements with det F <= 0 at one of their eight corner nodes, where the 2x2x2 Gauss rule does
// not look (trilinear hexahedra: dx/dxi at the reference corners xi in {-1, 1}^3).
int elements_inverted_at_a_node(const VolumeMesh& mesh, const Eigen::VectorXd& x) {
  static constexpr int kSign[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                      {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
  int count = 0;
  for (Eigen::Index e = 0; e < mesh.num_elements(); ++e) {
    for (int c = 0; c < 8; ++c) {
      Eigen::Matrix3d dx = Eigen::Matrix3d::Zero(), dX = Eigen::Matrix3d::Zero();
      for (int a = 0; a < 8; ++a) {
        Eigen::Vector3d dN;
        for (int d = 0; d < 3; ++d) {
          double v = 0.125 * kSign[a][d];
          for (int o = 0; o < 3; ++o)
            if (o != d) v *= 1.0 + kSign[a][o] * kSign[c][o];
          dN(d) = v;
        }
        const int n = mesh.elements(e, a);
        dx += x.segment<3>(3 * n) * dN.transpose();
        dX += mesh.vertices.row(n).transpose() * dN.transpose();
      }
      if (dx.determinant() / dX.determinant() <= 0.0) {
        ++count;
        break;
      }
    }
  }
  return count;
}

// Paper 000 Fig. 3 shows a scrambled cube recovering its rest shape. Over 20 seeds that is what
// most do, but not all: the discrete energy (no self-contact, 2x2x2 Gauss points) has other
// minima, e.g. a free cube corner pushed inside its own element, inverted near the corner node
// where no quadrature point looks (docs/experiments.md). So each seed that converges is checked
// to be either the rest shape to 1e-4 of the element edge (energy ~ 0), or a strict local
// minimum (positive energy, unprojected Hessian positive definite on the free DOFs): Newton
// never stops at a saddle or a non-minimum.
TEST(Experiments, ScrambleRecoversTheRestShapeOrProvesAnotherMinimum) {
  int recovered = 0, other_minima = 0, unconverged = 0;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    ScrambleConfig c;
    c.seed = seed;
    c.max_iterations = 5000;  // the slowest seeds creep into another minimum for ~3,000 iterations
    const ScrambleResult r = run_scramble(c);
    EXPECT_GT(r.inverted_at_start, r.elements / 2) << "seed " << seed << " barely scrambled";
    // Energy scale E h^3 (one element at unit strain); the rest minimum has energy 0.
    const double scale = c.E * std::pow(r.edge_length, 3);
    std::string outcome;
    if (!r.report.converged) {
      ++unconverged;
      outcome = "not converged: " + r.report.failure;
    } else if (r.energy < 1e-9 * scale) {
      ++recovered;
      EXPECT_LT(r.max_error, 1e-4 * r.edge_length) << "seed " << seed;
      EXPECT_GT(r.min_quadrature_J, 0.999) << "seed " << seed;
      outcome = "rest shape";
    } else {
      ++other_minima;
      const double lambda_min = smallest_free_eigenvalue(c, r);
      EXPECT_GT(lambda_min, 0.0) << "seed " << seed << ": converged to a point that is not a strict minimum";
      const VolumeMesh mesh =
          box_lattice(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), Eigen::Vector3i::Constant(c.cells));
      outcome = fmt::format("another minimum (energy {:.3g}, smallest Hessian eigenvalue {:.3g}, min Gauss-point J {:.3f}, "
                            "{} elements inverted at a node)",
                            r.energy, lambda_min, r.min_quadrature_J, elements_inverted_at_a_node(mesh, r.x));
    }
    std::printf("scramble %d^3 seed %2llu: %d/%ld inverted at start, %4d Newton, residual %.1e, max error %.1e: %s\n",
                c.cells, static_cast<unsigned long long>(seed), r.inverted_at_start, static_cast<long>(r.elements),
                r.report.iterations, r.report.residual, r.max_error, outcome.c_str());
  }
  std::printf("scramble: %d of 20 recovered the rest shape, %d other minima, %d not converged\n", recovered, other_minima,
              unconverged);
  // Observed: 16 of 20 at 4^3, and every seed converged within the cap. Regression guards, not
  // claims of the paper.
  EXPECT_EQ(unconverged, 0);
  EXPECT_GE(recovered, 12);
}

// The other minima at nu = 0.49 come with the stiff volume term: below it the same 20 scrambles
// all find the rest shape (about 20-100 Newton iterations each, against 100-3,000 at 0.49).
TEST(Experiments, ScrambleRecoversTheRestShapeForEverySeedAtLowerPoissonRatios) {
  for (double nu : {0.3, 0.45}) {
    int recovered = 0;
    for (std::uint64_t seed = 1; seed <= 20; ++seed) {
      ScrambleConfig c;
      c.seed = seed;
      c.nu = nu;
      const ScrambleResult r = run_scramble(c);
      const bool rest = r.report.converged && r.max_error < 1e-4 * r.edge_length;
      EXPECT_TRUE(rest) << "nu " << nu << " seed " << seed << ": " << r.report.iterations << " Newton, energy "
                        << r.energy << ", max error " << r.max_error;
      recovered += rest;
    }
    std::printf("scramble 4^3 at nu = %.2f: %d of 20 recovered the rest shape\n", nu, recovered);
  }
}

}  // namespace
}  // namespace sinew
