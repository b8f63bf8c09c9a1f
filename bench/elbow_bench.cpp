// Paper 000 Fig. 2 / Fig. 10 elbow flexion as a benchmark: the shipped arm surface
// (examples/meshes/arm.obj) voxelised, flexed 0 -> 120 degrees by two capsule bones with
// reference-map self-contact. Prints, per frame, Newton and CG iterations and seconds beside
// the paper's per-step averages (SNH 13.7 Newton, 5,860 CG, 25.6 s; StVK + Kikuuwe 32 / 14,446 /
// 140.3 s; 45,809 hexahedra), then one summary row per run (hexahedra, volume change, bulges,
// gap, deepest penetration, contact status).
//
//   elbow_bench [--cell 0.02] [--frames 12] [--substeps 1] [--threads 1]
//               [--models snh,corot,stvk] [--nu 0.488] [--contact 1] [--linear pcg|cholmod]
//               [--newton-cap 200] [--surface PATH|analytic]
//
// --frames is the number of time steps (output frames) of the flexion, --substeps the flexion
// increments solved within each (contacts are detected at every converged increment).
// Iterations and seconds of a frame are summed over its increments, as a paper "time step".
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <tbb/global_control.h>
#include <vector>

#include "sinew/core/error.hpp"
#include "experiments/elbow_experiment.hpp"

namespace {

using namespace sinew;

const std::map<std::string, std::string> kModels = {
    {"snh", "stable_neo_hookean"}, {"corot", "corotational"}, {"stvk", "stvk_kikuuwe"}};

std::vector<std::string> split(const std::string& list) {
  std::vector<std::string> out;
  std::stringstream in(list);
  for (std::string item; std::getline(in, item, ',');)
    if (!item.empty()) out.push_back(item);
  return out;
}

const PaperElbowFigure* paper_figure(const std::string& family) {
  for (const auto& p : kPaperElbow)
    if (family == p.family) return &p;
  return nullptr;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Elbow flexion benchmark (paper 000 Fig. 2 / Fig. 10)"};
  ElbowConfig base;
  base.arm_surface = std::filesystem::path(SINEW_EXAMPLES) / "meshes" / "arm.obj";
  base.cell_size = 0.02;
  base.frames = 12;
  std::string models = "snh,corot,stvk", nus = "0.488", linear = "pcg", surface;
  int threads = 1, newton_cap = 200;
  bool contact = true;
  app.add_option("--cell", base.cell_size, "lattice cell size (m)");
  app.add_option("--frames", base.frames, "time steps from 0 to 120 degrees");
  app.add_option("--substeps", base.substeps, "flexion increments per time step");
  app.add_option("--threads", threads, "TBB threads (0: all)");
  app.add_option("--models", models, "comma list of snh, corot, stvk");
  app.add_option("--nu", nus, "comma list of Poisson ratios");
  app.add_option("--contact", contact, "reference-map self-contact on (1) or off (0)");
  app.add_option("--refine", base.refine_contact, "local optimisation of contact targets on the deformed surface (0/1)");
  app.add_option("--stiffness", base.contact_stiffness, "self-contact penalty (Pa/m; 0: 50 E / cell)");
  app.add_option("--linear", linear, "linear solver: pcg (the paper's block-Jacobi CG) or cholmod");
  app.add_option("--newton-cap", newton_cap, "Newton iterations per increment");
  app.add_option("--surface", surface, "arm surface to voxelise (default examples/meshes/arm.obj; 'analytic': arm_sdf())");
  CLI11_PARSE(app, argc, argv);

  std::unique_ptr<tbb::global_control> limit;
  if (threads > 0)
    limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, static_cast<size_t>(threads));
  if (surface == "analytic") base.arm_surface.clear();
  else if (!surface.empty()) base.arm_surface = surface;
  base.self_contact = contact;
  base.bone_radius = std::max(0.016, 1.05 * base.cell_size);  // a ring of vertices around each bone axis

  struct Row {
    std::string model;
    double nu;
    ElbowRun run;
  };
  std::vector<Row> rows;
  try {
    for (const std::string& m : split(models)) {
      const auto it = kModels.find(m);
      if (it == kModels.end()) throw Error("unknown model '" + m + "' (snh, corot, stvk)", "--models");
      for (const std::string& nu_text : split(nus)) {
        ElbowConfig c = base;
        c.family = it->second;
        c.nu = std::stod(nu_text);
        if (m == "stvk") c.parameters["kappa"] = 8e8;  // Fig. 10's compression resistance
        c.solver = paper_solver(1e-3, newton_cap);
        c.solver.linear.kind = linear;
        c.solver.linear.max_iterations = 20000;
        const PaperElbowFigure* paper = paper_figure(c.family);
        std::printf("\n%s, nu %.3f, cell %.1f mm, %d frames x %d increments, contact %s, %s, %d thread(s)\n", c.family.c_str(),
                    c.nu, 1e3 * c.cell_size, c.frames, c.substeps, contact ? "on" : "off", linear.c_str(), threads);
        std::printf("%5s %9s %7s %8s %8s %9s %9s %8s %8s %8s %9s\n", "frame", "converged", "Newton", "CG", "seconds", "volume%",
                    "biceps", "forearm", "gap", "depth", "contacts");
        std::fflush(stdout);
        ElbowRun run = run_elbow(c, [&](const ElbowFrame& f) {
          std::printf("%5d %9s %7d %8d %8.2f %+9.2f %6.2f mm %5.2f mm %5.1f mm %5.2f mm (surface %5.2f mm) %9d  deepest at rest (%.3f, %.3f, %.3f)%s%s\n", f.solve.frame,
                      f.solve.converged ? "yes" : "NO", f.solve.newton_iterations, f.solve.linear_iterations, f.solve.seconds,
                      f.volume_change_percent, 1e3 * f.biceps_bulge, 1e3 * f.forearm_bulge, 1e3 * f.gap, 1e3 * f.max_depth, 1e3 * f.max_surface_depth, f.contacts_active,
                      f.deepest_rest.x(), f.deepest_rest.y(), f.deepest_rest.z(),
                      f.solve.failure.empty() ? "" : "  ", f.solve.failure.c_str());
          std::fflush(stdout);
        });
        std::printf("mean per frame: %.1f Newton, %.0f CG, %.2f s on %ld hexahedra", run.mean_newton(), run.mean_linear(),
                    run.mean_seconds(), static_cast<long>(run.elements));
        if (paper)
          std::printf("   (paper: %.1f Newton, %.0f CG, %.1f s per step on %ld hexahedra)", paper->newton, paper->cg,
                      paper->seconds, kPaperElbowHexes);
        std::printf("\n");
        rows.push_back({m, c.nu, std::move(run)});
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "elbow_bench: %s\n", e.what());
    return 1;
  }

  std::printf("\nsummary (after 120 degrees; in contact: gap < half a cell; interpenetrating: a sample deeper than a quarter cell)\n");
  std::printf("%-6s %6s %8s %10s %9s %9s %9s %8s %8s %11s %16s %7s %8s %8s\n", "model", "nu", "hexes", "converged", "volume%",
              "biceps", "forearm", "gap", "depth", "in contact", "interpenetrating", "Newton", "CG", "s/frame");
  for (const Row& r : rows) {
    const ElbowFrame& last = r.run.frames.back();
    int converged = 0;
    for (const auto& f : r.run.frames) converged += f.solve.converged;
    std::printf("%-6s %6.3f %8ld %6d/%-3zu %+9.2f %6.2f mm %6.2f mm %5.1f mm %5.2f mm %11s %16s %7.1f %8.0f %8.2f\n",
                r.model.c_str(), r.nu, static_cast<long>(r.run.elements), converged, r.run.frames.size(),
                r.run.volume_change_percent(), 1e3 * r.run.biceps_bulge(), 1e3 * r.run.forearm_bulge(), 1e3 * last.gap,
                1e3 * last.max_depth, r.run.in_contact() ? "yes" : "no", r.run.interpenetrating() ? "yes" : "no",
                r.run.mean_newton(), r.run.mean_linear(), r.run.mean_seconds());
  }
  for (const auto& p : kPaperElbow)
    std::printf("paper  %6.3f %8ld %10s %9s %9s %9s %8s %8s %11s %16s %7.1f %8.0f %8.1f  (%s)\n", 0.488, kPaperElbowHexes, "", "",
                "", "", "", "", "", "", p.newton, p.cg, p.seconds, p.family);
  return 0;
}
