// PCG preconditioners on hexahedral and tetrahedral meshes of one bar as the mesh is refined:
// CG iterations per Newton step and linear-solve time per Newton iteration (preconditioner setup
// included) for each preconditioner, in one run, printed as a Markdown table.
//
//   preconditioner_bench [--sizes 4,8,16] [--elements tet,hex]
//                        [--preconditioners block_jacobi,multigrid,amg] [--steps 3] [--repeats 3]
//                        [--threads N]
//
// The bar: [0,1] x [0,1] x [0,2] in n x n x 2n cells (hexahedra, or each split into six
// tetrahedra), stable Neo-Hookean with E = 1e5 and nu = 0.49, bottom face pinned, top face
// moved by (0.05, 0, -0.05) per load step; Sinew's Newton with its default settings (relative
// test, linear tolerance 1e-4). Iteration counts are deterministic; times are the median over
// --repeats runs of the whole solve. "multigrid" runs on hexahedra only (on tetrahedra it is
// block-Jacobi).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fmt/format.h>
#include <sstream>
#include <string>
#include <tbb/global_control.h>
#include <vector>

#include "sinew/assembly/problem.hpp"
#include "sinew/core/error.hpp"
#include "sinew/forms/elastic_form.hpp"
#include "sinew/material/families/stable_neo_hookean.hpp"
#include "sinew/mesh/lattice.hpp"
#include "sinew/mesh/selection.hpp"
#include "sinew/motion/prescribed_motion.hpp"
#include "sinew/solver/linear_solver.hpp"
#include "sinew/solver/newton.hpp"

namespace {

using namespace sinew;

struct Result {
  std::string elements, preconditioner;
  int n = 0;
  Eigen::Index element_count = 0, dofs = 0;
  bool converged = true;
  int newton = 0, cg = 0, max_cg = 0;
  std::vector<double> solve_seconds, assembly_seconds;  // per repeat, whole run
  std::string failure;  // the error that stopped the case, if any
};

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : (v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]));
}

std::vector<std::string> split(const std::string& list) {
  std::vector<std::string> out;
  std::stringstream ss(list);
  for (std::string item; std::getline(ss, item, ',');)
    if (!item.empty()) out.push_back(item);
  return out;
}

// The vertices on the plane z = height (outward normal (0, 0, normal_z)) moved by `motion`.
KinematicCondition face(const Eigen::MatrixX3d& rest, double height, double normal_z, RigidMotion motion, const std::string& name) {
  KinematicCondition c;
  c.vertices = select_vertices(rest, PlaneSelector{{0, 0, height}, {0, 0, normal_z}}, name);
  c.motion = std::move(motion);
  c.source = name;
  return c;
}

// One run of all load steps; adds its counts (first repeat) and times to r.
void run(const std::string& elements, int n, const std::string& preconditioner, int steps, bool first, Result& r) {
  VolumeMesh mesh = box_lattice(Eigen::Vector3d::Zero(), Eigen::Vector3d(1, 1, 2), Eigen::Vector3i(n, n, 2 * n));
  if (elements == "tet") mesh = tetrahedralize_hexes(mesh);
  auto disc = std::make_shared<Discretization>(std::move(mesh));
  const VolumeMesh& m = disc->mesh();
  Problem problem(m.num_vertices());
  const double E = 1e5, nu = 0.49, lambda = E * nu / ((1 + nu) * (1 - 2 * nu)), mu = E / (2 * (1 + nu));
  problem.add_form(std::make_shared<ElasticForm>(disc, std::make_shared<StableNeoHookean>(lambda, mu)));
  problem.set_discretization(disc);
  const std::vector<KinematicCondition> bcs = {face(m.vertices, 0.0, -1.0, Pinned{}, "bottom"),
                                               face(m.vertices, 2.0, 1.0, Translation{{0.05, 0, -0.05}}, "top")};
  LinearSolverSettings ls;
  ls.kind = "pcg";
  ls.preconditioner = preconditioner;
  auto linear = make_linear_solver(ls);
  Eigen::VectorXd x = m.rest_positions();
  double solve = 0.0, assembly = 0.0;
  for (int step = 1; step <= steps; ++step) {
    std::vector<char> fixed(static_cast<size_t>(x.size()), 0);
    apply_kinematics(bcs, m.vertices, step, x, fixed);
    problem.set_fixed(fixed);
    const NewtonReport nr = newton_solve(problem, x, *linear, NewtonSettings{}, [&](const NewtonIterate& it) {
      if (first) r.max_cg = std::max(r.max_cg, it.linear_iterations);
    });
    solve += nr.solve_seconds;
    assembly += nr.assembly_seconds;
    if (first) {
      r.newton += nr.iterations;
      r.cg += nr.linear_iterations;
      r.converged = r.converged && nr.converged;
    }
  }
  if (first) {
    r.element_count = m.num_elements();
    r.dofs = 3 * m.num_vertices();
  }
  r.solve_seconds.push_back(solve);
  r.assembly_seconds.push_back(assembly);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"PCG preconditioners on hexahedral and tetrahedral bars as the mesh is refined"};
  std::string sizes = "4,8,16", elements = "tet,hex", preconditioners = "block_jacobi,multigrid,amg";
  int steps = 3, repeats = 3, threads = 0;
  app.add_option("--sizes", sizes, "cells across the bar (n x n x 2n), comma-separated");
  app.add_option("--elements", elements, "tet, hex or both");
  app.add_option("--preconditioners", preconditioners, "PCG preconditioners to compare (comma-separated)");
  app.add_option("--steps", steps, "load steps")->check(CLI::PositiveNumber);
  app.add_option("--repeats", repeats, "runs per case; times are the median")->check(CLI::PositiveNumber);
  app.add_option("--threads", threads, "oneTBB threads (0: all cores)");
  CLI11_PARSE(app, argc, argv);
  std::unique_ptr<tbb::global_control> limit;
  if (threads > 0) limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, threads);

  std::vector<Result> results;
  try {
    for (const std::string& kind : split(elements)) {
      if (kind != "tet" && kind != "hex") throw Error("unknown element kind '" + kind + "' (tet, hex)", "--elements");
      for (const std::string& size : split(sizes)) {
        const int n = std::stoi(size);
        for (const std::string& pc : split(preconditioners)) {
          if (pc == "multigrid" && kind == "tet") continue;  // no lattice grid: it is block_jacobi there
          Result r;
          r.elements = kind;
          r.preconditioner = pc;
          r.n = n;
          try {
            for (int k = 0; k < repeats; ++k) {
              run(kind, n, pc, steps, k == 0, r);
              std::fprintf(stderr, "%s n=%d %s: run %d/%d, solve %.3f s\n", kind.c_str(), n, pc.c_str(), k + 1, repeats,
                           r.solve_seconds.back());
            }
          } catch (const Error& e) {  // one case failing (a preconditioner's error) leaves the others
            r.failure = e.what();
            std::fprintf(stderr, "%s n=%d %s: failed: %s\n", kind.c_str(), n, pc.c_str(), e.what());
          }
          results.push_back(std::move(r));
        }
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "preconditioner_bench: error: %s\n", e.what());
    return 1;
  }

  std::printf("\nBar [0,1]x[0,1]x[0,2], n x n x 2n cells, stable Neo-Hookean E = 1e5, nu = 0.49, %d load steps, "
              "Newton defaults (linear tolerance 1e-4); times: median of %d runs\n\n",
              steps, repeats);
  std::printf("| elements | n | elements | DOFs | preconditioner | Newton its | CG / Newton it (max) | solve ms / Newton it | "
              "assembly ms / Newton it | converged |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|\n");
  for (const Result& r : results) {
    if (!r.failure.empty()) {
      std::printf("| %s | %d | | | %s | failed: %s |||||\n", r.elements.c_str(), r.n, r.preconditioner.c_str(), r.failure.c_str());
      continue;
    }
    const double its = std::max(1, r.newton);
    std::printf("| %s | %d | %ld | %ld | %s | %d | %.1f (%d) | %.1f | %.1f | %s |\n", r.elements.c_str(), r.n,
                static_cast<long>(r.element_count), static_cast<long>(r.dofs), r.preconditioner.c_str(), r.newton,
                r.cg / its, r.max_cg, 1e3 * median(r.solve_seconds) / its, 1e3 * median(r.assembly_seconds) / its,
                r.converged ? "yes" : "no");
  }
  return 0;
}
