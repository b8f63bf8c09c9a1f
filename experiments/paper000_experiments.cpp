#include "experiments/paper000_experiments.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <numbers>
#include <random>

#include "sinew/core/error.hpp"
#include "sinew/element/discretization.hpp"
#include "sinew/forms/elastic_form.hpp"
#include "sinew/integrator/quasistatic_integrator.hpp"
#include "sinew/mesh/lattice.hpp"
#include "sinew/mesh/selection.hpp"
#include "sinew/solver/newton.hpp"

namespace sinew {

std::optional<PaperStretchFigure> paper_stretch_figure(const std::string& family) {
  for (const auto& f : kPaperStretch)
    if (family == f.family) return f;
  return std::nullopt;
}

std::optional<PaperTwistFigure> paper_twist_figure(const std::string& family) {
  for (const auto& f : kPaperTwist)
    if (family == f.family) return f;
  return std::nullopt;
}

SolverSpec paper_solver(double linear_tolerance, int max_newton_iterations) {
  SolverSpec s;
  s.newton.test = ConvergenceTest::Absolute;
  s.newton.absolute_tolerance = 1e-2;
  s.newton.max_iterations = max_newton_iterations;
  s.newton.linear_tolerance = linear_tolerance;
  s.linear.kind = "pcg";
  s.linear.preconditioner = "block_jacobi";
  s.projection = Projection::Clamp;
  return s;
}

namespace {

MaterialSpec normalised_material(const std::string& family, double E, double nu) {
  MaterialSpec m;
  m.family = family;
  m.target = YoungPoisson{E, nu};
  return m;
}

void require(bool ok, const std::string& what, const std::string& context) {
  if (!ok) throw Error(what, context);
}

}  // namespace

int stretch_length_cells(const StretchConfig& c) {
  return std::max(1, static_cast<int>(std::lround(c.length * c.diameter_cells)));
}

Scene stretch_scene(const StretchConfig& c) {
  const std::string where = "stretch experiment";
  require(c.diameter_cells >= 2, "diameter_cells must be at least 2", where);
  require(std::isfinite(c.length) && c.length > 0.0, "length must be positive", where);
  require(std::isfinite(c.stretch) && c.stretch > 0.0, "stretch must be positive", where);
  require(c.frames >= 1, "frames must be at least 1", where);
  Scene s;
  s.file = "experiment:stretch";
  s.mesh.source = CylinderShape{Eigen::Vector3d(0.0, 0.0, 0.5 * c.length), 0.5, c.length, 2};
  s.mesh.cells = Eigen::Vector3i(c.diameter_cells, c.diameter_cells, stretch_length_cells(c));
  s.material = normalised_material(c.family, c.E, c.nu);
  // Each end face moves outwards by half the elongation, spread evenly over the frames.
  const double per_frame = 0.5 * (c.stretch - 1.0) * c.length / c.frames;
  s.boundary.push_back({"bottom", PlaneSelector{Eigen::Vector3d::Zero(), -Eigen::Vector3d::UnitZ()},
                        Translation{Eigen::Vector3d(0.0, 0.0, -per_frame)}, {true, true, true}, {}});
  s.boundary.push_back({"top", PlaneSelector{Eigen::Vector3d(0.0, 0.0, c.length), Eigen::Vector3d::UnitZ()},
                        Translation{Eigen::Vector3d(0.0, 0.0, per_frame)}, {true, true, true}, {}});
  s.solver = c.solver;
  s.frames = c.frames;
  s.output.vtu = false;
  s.output.obj = false;
  return s;
}

Scene twist_scene(const TwistConfig& c) {
  const std::string where = "twist experiment";
  require(c.cells >= 1, "cells must be at least 1", where);
  require(c.frames >= 1, "frames must be at least 1", where);
  require(std::isfinite(c.degrees_per_frame), "degrees_per_frame must be finite", where);
  Scene s;
  s.file = "experiment:twist";
  s.mesh.source = BoxShape{Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones()};
  s.mesh.cells = Eigen::Vector3i::Constant(c.cells);
  s.material = normalised_material(c.family, c.E, c.nu);
  s.boundary.push_back({"bottom", PlaneSelector{Eigen::Vector3d::Zero(), -Eigen::Vector3d::UnitZ()}, Pinned{}, {true, true, true}, {}});
  s.boundary.push_back({"top", PlaneSelector{Eigen::Vector3d(0.0, 0.0, 1.0), Eigen::Vector3d::UnitZ()},
                        Rotation{Eigen::Vector3d(0.5, 0.5, 1.0), Eigen::Vector3d::UnitZ(),
                                 c.degrees_per_frame * std::numbers::pi / 180.0},
                        {true, true, true},
                        {}});
  s.solver = c.solver;
  s.frames = c.frames;
  s.output.vtu = false;
  s.output.obj = false;
  return s;
}

double ExperimentRun::volume_change_percent() const {
  if (frames.empty()) throw Error("no frame was run", "experiment");
  return 100.0 * (frames.back().volume / rest_volume - 1.0);
}

int ExperimentRun::total_newton() const {
  int n = 0;
  for (const auto& f : frames) n += f.newton_iterations;
  return n;
}

int ExperimentRun::total_linear() const {
  int n = 0;
  for (const auto& f : frames) n += f.linear_iterations;
  return n;
}

int ExperimentRun::frames_converged() const {
  return static_cast<int>(std::count_if(frames.begin(), frames.end(), [](const ExperimentFrame& f) { return f.converged; }));
}

double ExperimentRun::assembly_seconds() const {
  double t = 0.0;
  for (const auto& f : frames) t += f.assembly_seconds;
  return t;
}

double ExperimentRun::solve_seconds() const {
  double t = 0.0;
  for (const auto& f : frames) t += f.solve_seconds;
  return t;
}

double ExperimentRun::seconds() const {
  double t = 0.0;
  for (const auto& f : frames) t += f.seconds;
  return t;
}

namespace {

// Signed deformed volume: det F integrated with the element quadrature (exact for trilinear
// hexahedra, whose det F has degree <= 2 in each reference coordinate, and for tetrahedra).
double deformed_volume(const Discretization& disc, const Eigen::VectorXd& x) {
  double v = 0.0;
  for (Eigen::Index e = 0; e < disc.num_elements(); ++e)
    for (int q = 0; q < disc.quadrature_points(); ++q) v += disc.weight(e, q) * disc.deformation_gradient(e, q, x).determinant();
  return v;
}

}  // namespace

ExperimentRun run_experiment(const Scene& scene, const ExperimentOptions& options) {
  const std::string where = scene.file.string();
  if (scene.gravity.squaredNorm() > 0.0 || !scene.point_loads.empty() || !scene.tractions.empty())
    throw Error("the experiment runner supports kinematic boundaries only, not loads", where);
  const int frames = options.frames.value_or(scene.frames);
  if (frames < 1) throw Error("frames must be at least 1", where);

  auto disc = std::make_shared<Discretization>(build_scene_mesh(scene), where + ": /mesh");
  const VolumeMesh& mesh = disc->mesh();
  auto elastic = std::make_shared<ElasticForm>(disc, build_material(scene.material), scene.solver.projection);
  auto problem = std::make_shared<Problem>(mesh.num_vertices());
  problem->set_discretization(disc);
  problem->add_form(elastic);
  problem->set_matrix_free(scene.solver.linear.matrix_free);
  std::vector<KinematicCondition> kinematics;
  for (const auto& b : scene.boundary)
    kinematics.push_back({select_vertices(mesh.vertices, b.select, where + ": boundary " + b.name), b.motion,
                          where + ": boundary " + b.name + " motion", b.components, b.direction});
  PrescribedMotion motion = [&](double frame, Eigen::VectorXd& y, std::vector<char>& fixed) {
    apply_kinematics(kinematics, mesh.vertices, frame, y, fixed);
  };
  // The same load stepping as `sinew run` (predictor included), with motion splitting off.
  QuasistaticIntegrator integrator(problem, std::move(motion), nullptr, make_linear_solver(scene.solver.linear),
                                   scene.solver.newton, scene.solver.predictor, 0);

  ExperimentRun run;
  run.vertices = mesh.num_vertices();
  run.elements = mesh.num_elements();
  for (Eigen::Index e = 0; e < disc->num_elements(); ++e) run.rest_volume += disc->rest_volume(e);
  State state{mesh.rest_positions(), {}};
  const Eigen::VectorXd& x = state.x;
  for (int frame = 1; frame <= frames; ++frame) {
    const auto t0 = std::chrono::steady_clock::now();
    IterationProgress progress;
    if (options.on_iteration)
      progress = [&](int iteration, double residual) { options.on_iteration(frame, NewtonIterate{iteration, residual}); };
    const StepStats r = integrator.advance_frame(state, frame, progress);
    ExperimentFrame f;
    f.frame = frame;
    f.converged = r.converged;
    f.predicted = r.counter("predicted_steps") > 0.0;
    f.newton_iterations = r.newton_iterations;
    f.linear_iterations = r.linear_iterations;
    f.residual = r.residual;
    f.energy = r.energy;
    f.assembly_seconds = r.assembly_seconds;
    f.solve_seconds = r.solve_seconds;
    f.failure = r.failure;
    f.volume = deformed_volume(*disc, x);
    f.min_quadrature_J = min_quadrature_J(*disc, x);
    f.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    run.frames.push_back(f);
    if (options.on_frame) options.on_frame(run.frames.back());
  }
  run.x = state.x;
  run.x = std::move(x);
  return run;
}

double min_quadrature_J(const Discretization& disc, const Eigen::VectorXd& x) {
  if (x.size() != disc.num_dofs())
    throw Error(fmt::format("positions have {} entries, the mesh has {} DOFs", x.size(), disc.num_dofs()),
                "min_quadrature_J");
  double m = std::numeric_limits<double>::infinity();
  for (Eigen::Index e = 0; e < disc.num_elements(); ++e)
    for (int q = 0; q < disc.quadrature_points(); ++q) m = std::min(m, disc.deformation_gradient(e, q, x).determinant());
  return m;
}

std::array<int, 4> tetrahedral_corners(const VolumeMesh& mesh) {
  if (mesh.num_vertices() == 0) throw Error("empty mesh", "tetrahedral_corners");
  const Eigen::Vector3d lo = mesh.vertices.colwise().minCoeff(), hi = mesh.vertices.colwise().maxCoeff();
  const double tol = 1e-9 * (hi - lo).norm();
  // Corners (0,0,0), (1,1,0), (1,0,1), (0,1,1) of the bounding box, pairwise joined by face
  // diagonals: a regular tetrahedron.
  const std::array<Eigen::Vector3d, 4> corners{Eigen::Vector3d(lo.x(), lo.y(), lo.z()), Eigen::Vector3d(hi.x(), hi.y(), lo.z()),
                                               Eigen::Vector3d(hi.x(), lo.y(), hi.z()), Eigen::Vector3d(lo.x(), hi.y(), hi.z())};
  std::array<int, 4> out{};
  for (int c = 0; c < 4; ++c) {
    Eigen::Index best = 0;
    (mesh.vertices.rowwise() - corners[c].transpose()).rowwise().squaredNorm().minCoeff(&best);
    if ((mesh.vertices.row(best).transpose() - corners[c]).norm() > tol)
      throw Error(fmt::format("no vertex at bounding-box corner ({}, {}, {})", corners[c].x(), corners[c].y(), corners[c].z()),
                  "tetrahedral_corners");
    out[c] = static_cast<int>(best);
  }
  return out;
}

Eigen::VectorXd scramble_positions(const VolumeMesh& mesh, const std::array<int, 4>& pinned, double volume_factor,
                                   std::uint64_t seed) {
  if (!(std::isfinite(volume_factor) && volume_factor > 0.0))
    throw Error("volume factor must be positive", "scramble_positions");
  const Eigen::Vector3d lo = mesh.vertices.colwise().minCoeff(), hi = mesh.vertices.colwise().maxCoeff();
  const Eigen::Vector3d centre = 0.5 * (lo + hi);
  // Side lengths scaled by the cube root of the volume factor, about the same centre.
  const Eigen::Vector3d half = 0.5 * std::cbrt(volume_factor) * (hi - lo);
  std::mt19937_64 rng(seed);  // its output sequence is fixed by the standard
  auto uniform = [&] { return static_cast<double>(rng() >> 11) * 0x1.0p-53; };  // [0, 1)
  Eigen::VectorXd x = mesh.rest_positions();
  for (Eigen::Index v = 0; v < mesh.num_vertices(); ++v) {
    for (int i = 0; i < 3; ++i) x(3 * v + i) = centre(i) + half(i) * (2.0 * uniform() - 1.0);
  }
  for (int v : pinned) x.segment<3>(3 * v) = mesh.vertices.row(v).transpose();
  return x;
}

ScrambleResult run_scramble(const ScrambleConfig& c) {
  const std::string where = "scramble experiment";
  require(c.cells >= 1, "cells must be at least 1", where);
  VolumeMesh mesh = box_lattice(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), Eigen::Vector3i::Constant(c.cells));
  if (c.element == ElementKind::Tet4) mesh = tetrahedralize_hexes(mesh);
  auto disc = std::make_shared<Discretization>(mesh, where);
  auto form = std::make_shared<ElasticForm>(disc, build_material(normalised_material(c.family, c.E, c.nu)), c.projection);
  Problem problem(mesh.num_vertices());
  problem.set_discretization(disc);
  problem.add_form(form);

  ScrambleResult r;
  r.vertices = mesh.num_vertices();
  r.elements = mesh.num_elements();
  r.edge_length = 1.0 / c.cells;
  r.pinned = tetrahedral_corners(mesh);
  std::vector<char> fixed(disc->num_dofs(), 0);
  for (int v : r.pinned)
    for (int i = 0; i < 3; ++i) fixed[3 * v + i] = 1;
  problem.set_fixed(fixed);

  Eigen::VectorXd x = scramble_positions(mesh, r.pinned, c.volume_factor, c.seed);
  for (Eigen::Index e = 0; e < disc->num_elements(); ++e) {
    for (int q = 0; q < disc->quadrature_points(); ++q) {
      if (disc->deformation_gradient(e, q, x).determinant() <= 0.0) {
        ++r.inverted_at_start;
        break;
      }
    }
  }
  NewtonSettings settings;
  settings.test = ConvergenceTest::Absolute;
  settings.absolute_tolerance = c.tolerance;
  settings.max_iterations = c.max_iterations;
  settings.linear_tolerance = c.linear_tolerance;
  auto linear = make_linear_solver(c.linear);
  r.report = newton_solve(problem, x, *linear, settings);
  r.energy = r.report.energy;
  r.max_error = (x - mesh.rest_positions()).reshaped(3, mesh.num_vertices()).colwise().norm().maxCoeff();
  r.min_quadrature_J = min_quadrature_J(*disc, x);
  r.x = std::move(x);
  return r;
}

}  // namespace sinew
