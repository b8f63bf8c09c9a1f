#pragma once
// Benchmarks with known answers (docs/verification.md): Cook's membrane against a published
// mesh-convergence table and a thick-walled cylinder against the 1-D radial solution. Shared by
// the default tests (small sizes) and the `slow` tests (full tables).
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <functional>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "sinew/assembly/problem.hpp"
#include "sinew/element/discretization.hpp"
#include "sinew/forms/elastic_form.hpp"
#include "sinew/forms/external_force_form.hpp"
#include "sinew/material/material.hpp"
#include "sinew/material/spec.hpp"
#include "sinew/mesh/volume_mesh.hpp"
#include "sinew/model/scene.hpp"
#include "sinew/run/simulation.hpp"
#include "sinew/solver/linear_solver.hpp"
#include "sinew/solver/newton.hpp"

namespace sinew::verification {

// The compressible Neo-Hookean energy of the reference Cook's membrane computation
// (Pelteret & McBride, deal.II code gallery "Quasi-static finite-strain compressible
// elasticity", 2016, doi:10.5281/zenodo.1228964), an isochoric/volumetric split:
//   Psi = mu/2 (J^(-2/3) I_C - 3) + kappa/4 (J^2 - 1 - 2 log J),
// kappa = 2 mu (1 + nu) / (3 (1 - 2 nu)): Lame parameters (kappa - 2/3 mu, mu). Not in Sinew's
// catalog (its neo_hookean is mu/2 (I_C - 3) - mu log J + lambda/2 log^2 J); written here in
// stretches so the benchmark solves the reference's own energy.
class SplitNeoHookean final : public StretchMaterial {
 public:
  SplitNeoHookean(double mu, double kappa) : mu_(mu), kappa_(kappa) {}
  std::string name() const override { return "split_neo_hookean (test)"; }
  Domain domain() const override { return Domain::PositiveJ; }
  double psi_stretch(const Vec3& s) const override {
    const double J = s.prod(), A = std::pow(J, -2.0 / 3.0);
    return 0.5 * mu_ * (A * s.squaredNorm() - 3.0) + 0.25 * kappa_ * (J * J - 1.0 - 2.0 * std::log(J));
  }
  Vec3 grad_stretch(const Vec3& s) const override {
    const double J = s.prod(), A = std::pow(J, -2.0 / 3.0), I = s.squaredNorm();
    Vec3 g;
    for (int i = 0; i < 3; ++i)
      g(i) = 0.5 * mu_ * A * (2.0 * s(i) - 2.0 / 3.0 * I / s(i)) + 0.5 * kappa_ * (J * J - 1.0) / s(i);
    return g;
  }
  Mat3 hess_stretch(const Vec3& s) const override {
    const double J = s.prod(), A = std::pow(J, -2.0 / 3.0), I = s.squaredNorm();
    Mat3 h;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        const double d = i == j ? 1.0 : 0.0;
        // d/ds_j of mu/2 A (2 s_i - 2/3 I / s_i), with dA/ds_j = -2/3 A / s_j
        const double iso = -2.0 / 3.0 * A / s(j) * (2.0 * s(i) - 2.0 / 3.0 * I / s(i)) +
                           A * (2.0 * d - 4.0 / 3.0 * s(j) / s(i) + d * 2.0 / 3.0 * I / (s(i) * s(i)));
        // d/ds_j of kappa/2 (J^2 - 1) / s_i
        const double vol = 2.0 * J * J / (s(i) * s(j)) - d * (J * J - 1.0) / (s(i) * s(i));
        h(i, j) = 0.5 * mu_ * iso + 0.5 * kappa_ * vol;
      }
    return h;
  }

 private:
  double mu_, kappa_;
};

// Cook's membrane: the panel with corners (0,0), (48,44), (48,60), (0,44) (mm), one layer of
// thickness 1 in z, N x N trilinear hexahedra mapped from the unit square as in the reference
// (x = 48 u; y between the lower edge 44/48 x and the upper edge 44 + 16/48 x at fraction v).
// Vertex (i, j, k) has index k (N+1)^2 + j (N+1) + i.
inline VolumeMesh cook_membrane_mesh(int N, double thickness = 1.0) {
  VolumeMesh mesh;
  mesh.kind = ElementKind::Hex8;
  const int n = N + 1;
  mesh.vertices.resize(2 * n * n, 3);
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const double x = 48.0 * i / N, t = static_cast<double>(j) / N;
        const double y = (1.0 - t) * (44.0 / 48.0) * x + t * (44.0 + (16.0 / 48.0) * x);
        mesh.vertices.row(k * n * n + j * n + i) << x, y, k * thickness;
      }
  mesh.elements.resize(N * N, 8);
  auto id = [&](int i, int j, int k) { return k * n * n + j * n + i; };
  for (int j = 0; j < N; ++j)
    for (int i = 0; i < N; ++i)
      mesh.elements.row(j * N + i) << id(i, j, 0), id(i + 1, j, 0), id(i + 1, j + 1, 0), id(i, j + 1, 0),
          id(i, j, 1), id(i + 1, j, 1), id(i + 1, j + 1, 1), id(i, j + 1, 1);
  return mesh;
}

// A solve through the C++ API: elastic energy, dead loads, prescribed DOFs, load steps.
struct StaticSolve {
  Eigen::VectorXd x, gradient;  // solution and the elastic energy's gradient there
  bool converged = true;
  int iterations = 0;
  std::string failure;
};

// Minimises the elastic energy minus loads.dot(x) with `fixed` DOFs held at prescribed(step)
// (called for step = 1..steps; it sets x's prescribed entries) and the load ramped as step/steps.
inline StaticSolve solve_static(const VolumeMesh& mesh, std::shared_ptr<const Material> material,
                                const std::vector<char>& fixed, const Eigen::VectorXd& loads, int steps,
                                double force_scale,
                                const std::function<void(double, Eigen::VectorXd&)>& prescribe = {}) {
  auto disc = std::make_shared<Discretization>(mesh, "verification");
  Problem problem(mesh.num_vertices());
  problem.set_discretization(disc);
  auto elastic = std::make_shared<ElasticForm>(disc, material, Projection::Clamp);
  auto load = std::make_shared<ExternalForceForm>(Eigen::VectorXd::Zero(loads.size()));
  problem.add_form(elastic);
  problem.add_form(load);
  const double size = (mesh.vertices.colwise().maxCoeff() - mesh.vertices.colwise().minCoeff()).norm();
  problem.set_scales({size, force_scale});
  problem.set_fixed(fixed);
  auto linear = make_linear_solver(LinearSolverSettings{});
  NewtonSettings ns;
  ns.residual_tolerance = 1e-9;
  ns.step_tolerance = 1e-7;
  StaticSolve out;
  out.x = mesh.rest_positions();
  for (int s = 1; s <= steps; ++s) {
    const double a = static_cast<double>(s) / steps;
    load->forces() = a * loads;
    if (prescribe) prescribe(a, out.x);
    const NewtonReport report = newton_solve(problem, out.x, *linear, ns);
    out.iterations += report.iterations;
    if (!report.converged) {
      out.converged = false;
      out.failure = "step " + std::to_string(s) + ": " + report.failure;
      break;
    }
  }
  out.gradient = Eigen::VectorXd::Zero(out.x.size());
  elastic->add_gradient(out.x, out.gradient);
  return out;
}

// Cook's membrane as in the reference: clamped at x = 0, u_z = 0 everywhere (plane strain), a
// total vertical force of 1 N on the edge x = 48 as a dead traction of 1/16 N/mm^2 per unit rest
// area (the reference's "total force / rest area", fixed direction), in 10 load steps. Returns
// the vertical displacement of the corner (48, 60) (both its vertices).
struct CookResult {
  double tip = 0.0;
  bool converged = false;
  int iterations = 0;
  std::string failure;
};
// How the slab's thickness direction is treated:
// * PlaneStrain: u_z = 0 at every vertex (the setup);
// * FreeSlab: the reference's actual setup, the 1 mm slab with u_z free away from the clamp (nearly
//   plane stress); its symmetric solution is unstable at N >= 8 for a minimiser (see the docs);
// * HalfSlab: the same slab's symmetric solution as a half model: thickness 0.5, u_z = 0 on the
//   mid-plane z = 0 (a symmetry plane), the same traction, so the load (0.5 N) and the tip
//   deflection are those of the full slab constrained to stay symmetric.
enum class CookThickness { PlaneStrain, FreeSlab, HalfSlab };
inline CookResult solve_cook_membrane(int N, std::shared_ptr<const Material> material, double mu,
                                      CookThickness thickness_mode = CookThickness::PlaneStrain) {
  const double thickness = thickness_mode == CookThickness::HalfSlab ? 0.5 : 1.0;
  const VolumeMesh mesh = cook_membrane_mesh(N, thickness);
  const int n = N + 1;
  std::vector<char> fixed(3 * mesh.num_vertices(), 0);
  Eigen::VectorXd loads = Eigen::VectorXd::Zero(3 * mesh.num_vertices());
  const double traction = 1.0 / 16.0;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < n; ++j) {
      const int left = k * n * n + j * n, right = left + N;
      fixed[3 * left] = fixed[3 * left + 1] = 1;
      // The faces of the edge x = 48 are 16/N x thickness rectangles: A/4 of each to each corner.
      const double faces = (j == 0 || j == N) ? 1.0 : 2.0;
      loads(3 * right + 1) = faces * traction * (16.0 / N) * thickness / 4.0;
    }
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < n; ++j) fixed[3 * (k * n * n + j * n) + 2] = 1;
  if (thickness_mode == CookThickness::PlaneStrain)
    for (Eigen::Index v = 0; v < mesh.num_vertices(); ++v) fixed[3 * v + 2] = 1;
  if (thickness_mode == CookThickness::HalfSlab)
    for (int v = 0; v < n * n; ++v) fixed[3 * v + 2] = 1;  // the mid-plane z = 0
  const StaticSolve s = solve_static(mesh, std::move(material), fixed, loads, 10, mu * 60.0 * 60.0);
  CookResult r;
  r.converged = s.converged;
  r.iterations = s.iterations;
  r.failure = s.failure;
  const int tip0 = N * n + N, tip1 = n * n + N * n + N;
  r.tip = 0.5 * ((s.x(3 * tip0 + 1) - mesh.vertices(tip0, 1)) + (s.x(3 * tip1 + 1) - mesh.vertices(tip1, 1)));
  return r;
}

// Pelteret & McBride's tip displacements (mm) with Q1 elements, N = 1, 2, 4, ..., 64 elements per
// edge (README of the code-gallery entry), and their converged Q2 value.
inline double cook_reference_q1(int N) {
  switch (N) {
    case 2: return 8.72;
    case 4: return 12.02;
    case 8: return 13.61;
    case 16: return 14.13;
    case 32: return 14.28;
    case 64: return 14.32;
    default: return NAN;
  }
}
constexpr double kCookReferenceConverged = 14.33;
// The reference's material: mu = 422.5 kPa = 0.4225 N/mm^2, nu = 0.3.
constexpr double kCookMu = 0.4225, kCookNu = 0.3;
inline double cook_kappa() { return 2.0 * kCookMu * (1.0 + kCookNu) / (3.0 * (1.0 - 2.0 * kCookNu)); }

// ---- Thick-walled cylinder, plane strain, inner surface displaced radially ----

// The radial equilibrium of a plane-strain cylinder of the standard Neo-Hookean material
//   Psi = mu/2 (I_C - 3) - mu log J + lambda/2 log^2 J,
// deformation r(R): stretches lr = r', lt = r/R, lz = 1; nominal stresses
//   P_i = mu (l_i - 1/l_i) + lambda log(J) / l_i,  J = lr lt,
// equilibrium dP_R/dR + (P_R - P_T)/R = 0 with r(A) = a and P_R(B) = 0 (free outer surface).
// Solved by shooting on r'(A) with RK4 in R.
struct RadialSolution {
  double outer_radius = 0.0;  // r(B)
  double inner_PR = 0.0;      // P_R(A): nominal radial stress at the inner surface (negative: pressure)
};
inline RadialSolution cylinder_radial_solution(double A, double B, double a, double mu, double lambda,
                                               int steps = 4000) {
  auto stress = [&](double lr, double lt, double& PR, double& PT, double& dPR_dlr, double& dPR_dlt) {
    const double logJ = std::log(lr * lt);
    PR = mu * (lr - 1.0 / lr) + lambda * logJ / lr;
    PT = mu * (lt - 1.0 / lt) + lambda * logJ / lt;
    dPR_dlr = mu * (1.0 + 1.0 / (lr * lr)) + lambda * (1.0 - logJ) / (lr * lr);
    dPR_dlt = lambda / (lr * lt);
  };
  // y = (r, r'); y' = (r', r'')
  auto rhs = [&](double R, const Eigen::Vector2d& y) {
    double PR, PT, a11, a12;
    stress(y(1), y(0) / R, PR, PT, a11, a12);
    const double r2 = -((PR - PT) / R + a12 * (y(1) / R - y(0) / (R * R))) / a11;
    return Eigen::Vector2d(y(1), r2);
  };
  auto shoot = [&](double slope, Eigen::Vector2d& y) {
    y = Eigen::Vector2d(a, slope);
    const double h = (B - A) / steps;
    for (int i = 0; i < steps; ++i) {
      const double R = A + i * h;
      const Eigen::Vector2d k1 = rhs(R, y), k2 = rhs(R + h / 2, y + h / 2 * k1), k3 = rhs(R + h / 2, y + h / 2 * k2),
                            k4 = rhs(R + h, y + h * k3);
      y += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
    }
    double PR, PT, a11, a12;
    stress(y(1), y(0) / B, PR, PT, a11, a12);
    return PR;
  };
  // P_R(B) increases with the slope r'(A): bisection between a compressed and a stretched start.
  double lo = 0.2, hi = 3.0;
  Eigen::Vector2d y;
  for (int it = 0; it < 200 && hi - lo > 1e-15; ++it) {
    const double mid = 0.5 * (lo + hi);
    (shoot(mid, y) > 0.0 ? hi : lo) = mid;
  }
  const double slope = 0.5 * (lo + hi);
  shoot(slope, y);
  RadialSolution out;
  out.outer_radius = y(0);
  double PR, PT, a11, a12;
  stress(slope, a / A, PR, PT, a11, a12);
  out.inner_PR = PR;
  return out;
}

// The same cylinder under an internal follower pressure p (force per deformed area) with the
// outer surface free: the inner radius a is unknown too. The Cauchy radial stress at r = a is -p;
// in nominal terms (plane strain, Nanson: da = l_T l_Z dA) P_R(A) = -p a / A. For each trial a the
// displacement problem above gives P_R(A; a); the pressure problem's a solves
// P_R(A; a) + p a / A = 0, found by bisection (the left side is p at a = A and decreases: a
// Neo-Hookean plane-strain cylinder has no pressure maximum).
struct PressureSolution {
  double inner_radius = 0.0, outer_radius = 0.0;
};
inline PressureSolution cylinder_pressure_solution(double A, double B, double p, double mu, double lambda) {
  auto g = [&](double a) { return cylinder_radial_solution(A, B, a, mu, lambda).inner_PR + p * a / A; };
  double lo = A, hi = 1.5 * A;
  while (g(hi) > 0.0) hi = A + 2.0 * (hi - A);
  for (int it = 0; it < 60 && hi - lo > 1e-14 * A; ++it) {
    const double mid = 0.5 * (lo + hi);
    (g(mid) > 0.0 ? lo : hi) = mid;
  }
  PressureSolution out;
  out.inner_radius = 0.5 * (lo + hi);
  out.outer_radius = cylinder_radial_solution(A, B, out.inner_radius, mu, lambda).outer_radius;
  return out;
}

// The cylinders' material: Neo-Hookean at E = 1000, nu = 0.3, with the energy's own mu, lambda
// for the radial ODE.
struct CylinderMaterial {
  std::shared_ptr<const Material> material;
  double mu = 0.0, lambda = 0.0;
};
inline CylinderMaterial cylinder_material() {
  MaterialSpec spec;
  spec.family = "neo_hookean";
  spec.target = YoungPoisson{1000.0, 0.3};
  const auto built = build_material_detailed(spec);
  return {built.material, built.parameters.values.at("mu"), built.parameters.values.at("lambda")};
}

// A full annulus A <= R <= B, one layer of thickness `thickness` in z, Nr x Nt hexahedra.
// Vertex (i radial, j around, k) has index k Nr1 Nt + j Nr1 + i with Nr1 = Nr + 1.
inline VolumeMesh annulus_mesh(double A, double B, double thickness, int Nr, int Nt) {
  VolumeMesh mesh;
  mesh.kind = ElementKind::Hex8;
  const int n = Nr + 1;
  mesh.vertices.resize(2 * n * Nt, 3);
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < Nt; ++j)
      for (int i = 0; i < n; ++i) {
        const double R = A + (B - A) * i / Nr, t = 2.0 * std::numbers::pi * j / Nt;
        mesh.vertices.row(k * n * Nt + j * n + i) << R * std::cos(t), R * std::sin(t), k * thickness;
      }
  mesh.elements.resize(Nr * Nt, 8);
  auto id = [&](int i, int j, int k) { return k * n * Nt + (j % Nt) * n + i; };
  for (int j = 0; j < Nt; ++j)
    for (int i = 0; i < Nr; ++i)
      mesh.elements.row(j * Nr + i) << id(i, j, 0), id(i + 1, j, 0), id(i + 1, j + 1, 0), id(i, j + 1, 0),
          id(i, j, 1), id(i + 1, j, 1), id(i + 1, j + 1, 1), id(i, j + 1, 1);
  return mesh;
}

struct CylinderResult {
  double outer_radius = 0.0;  // mean deformed radius of the outer vertices
  double inner_force = 0.0;   // radial resultant the inner condition exerts on the body (> 0 outwards)
  bool converged = false;
  std::string failure;
};
// Inner surface moved to radius a (all three coordinates prescribed, z held), u_z = 0 on every
// vertex (plane strain), outer surface free; the inner displacement ramped over `steps` steps.
inline CylinderResult solve_cylinder(double A, double B, double a, std::shared_ptr<const Material> material,
                                     double mu, int Nr, int Nt, int steps) {
  const double thickness = (B - A) / Nr;
  const VolumeMesh mesh = annulus_mesh(A, B, thickness, Nr, Nt);
  const int n = Nr + 1;
  std::vector<char> fixed(3 * mesh.num_vertices(), 0);
  std::vector<int> inner, outer;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < Nt; ++j) {
      inner.push_back(k * n * Nt + j * n);
      outer.push_back(k * n * Nt + j * n + Nr);
    }
  for (int v : inner) fixed[3 * v] = fixed[3 * v + 1] = 1;
  for (Eigen::Index v = 0; v < mesh.num_vertices(); ++v) fixed[3 * v + 2] = 1;
  const Eigen::MatrixX3d rest = mesh.vertices;
  auto prescribe = [&](double amplitude, Eigen::VectorXd& x) {
    const double scale = 1.0 + amplitude * (a / A - 1.0);
    for (int v : inner) x.segment<2>(3 * v) = scale * rest.row(v).head<2>().transpose();
  };
  const StaticSolve s = solve_static(mesh, std::move(material), fixed, Eigen::VectorXd::Zero(3 * mesh.num_vertices()),
                                     steps, mu * B * B, prescribe);
  CylinderResult r;
  r.converged = s.converged;
  r.failure = s.failure;
  for (int v : outer) r.outer_radius += s.x.segment<2>(3 * v).norm() / outer.size();
  // The condition's force on the body (its reaction) is the elastic gradient at its DOFs.
  for (int v : inner) r.inner_force += s.gradient.segment<2>(3 * v).dot(rest.row(v).head<2>().transpose().normalized());
  return r;
}

// ---- Thick-walled cylinder under internal pressure, through the scene file ----

// examples/verification/thick_cylinder.json on the quarter annulus of Nr radial x 2 Nr
// circumferential hexahedra (make_thick_cylinder_mesh.py writes the mesh into `dir`): symmetry
// rollers, plane strain, a follower pressure on the inner surface, all as a user writes them.
struct PressureCylinderRun {
  double pressure = 0.0, thickness = 0.0;
  double inner_radius = 0.0, outer_radius = 0.0;  // mean deformed radii of the inner/outer vertices
  double symmetry_reaction = 0.0;  // y-reaction of the roller on y = 0 (the hoop force's balance)
  double mu = 0.0, lambda = 0.0;
  bool converged = false;
  std::string failure;
};
inline PressureCylinderRun run_pressure_cylinder(int Nr, const std::filesystem::path& dir) {
  const std::filesystem::path folder = std::filesystem::path(SINEW_EXAMPLES) / "verification";
  const std::filesystem::path mesh = dir / ("thick_cylinder_N" + std::to_string(Nr) + ".msh");
  const std::string command = "python3 '" + (folder / "make_thick_cylinder_mesh.py").string() + "' " +
                              std::to_string(Nr) + " '" + mesh.string() + "'";
  if (std::system(command.c_str()) != 0) throw std::runtime_error("failed: " + command);
  std::ifstream in(folder / "thick_cylinder.json");
  std::stringstream text;
  text << in.rdbuf();
  nlohmann::json j = nlohmann::json::parse(text.str());
  j["mesh"]["file"] = mesh.string();
  const Scene scene = parse_scene(j, folder / "thick_cylinder.json");
  const RunSummary summary = run_scene(scene, RunOptions{});
  PressureCylinderRun out;
  out.converged = summary.all_converged();
  if (!out.converged && !summary.frames.empty()) out.failure = summary.frames.back().failure;
  out.pressure = j["loads"]["pressure"][0]["pressure"].get<double>();
  out.thickness = 1.0 / Nr;  // (B - A) / Nr, as the mesh generator makes it
  const auto built = build_material_detailed(scene.material);
  out.mu = built.parameters.values.at("mu");
  out.lambda = built.parameters.values.at("lambda");
  const VolumeMesh rest = build_scene_mesh(scene);
  int inner = 0, outer = 0;
  for (Eigen::Index v = 0; v < rest.num_vertices(); ++v) {
    const double R = rest.vertices.row(v).head<2>().norm();
    const double r = summary.x.segment<2>(3 * v).norm();
    if (std::abs(R - 1.0) < 1e-9) out.inner_radius += r, ++inner;
    if (std::abs(R - 2.0) < 1e-9) out.outer_radius += r, ++outer;
  }
  out.inner_radius /= inner;
  out.outer_radius /= outer;
  if (!summary.frames.empty()) out.symmetry_reaction = summary.frames.back().reactions[0](1);
  return out;
}

}  // namespace sinew::verification
