// Dynamics experiments as a benchmark: the drop test (examples/drop_test.json) at several
// resolutions with both integrators and both linear solvers, and the released pre-stretched
// block of the energy test, each printed as ms per frame, Newton and linear (CG) iterations per
// frame and time step, and the experiment's own figures (volume ratios, energy decay).
//
//   dynamics_bench [--sizes 4,8,12] [--frames 60] [--threads N]
#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <fmt/format.h>
#include <fstream>
#include <nlohmann/json.hpp>
#include <tbb/global_control.h>

#include "sinew/core/error.hpp"
#include "sinew/forms/elastic_form.hpp"
#include "sinew/material/families/stable_neo_hookean.hpp"
#include "sinew/mesh/lattice.hpp"
#include "sinew/run/simulation.hpp"
#include "sinew/integrator/time_stepper.hpp"

namespace {

using namespace sinew;

struct Row {
  std::string experiment, integrator, solver;
  Eigen::Index vertices = 0, elements = 0;
  int frames = 0, steps = 0, newton = 0, linear = 0;
  double seconds = 0.0;
  std::string figures;
  bool converged = false;
};

Row run(const std::string& experiment, const nlohmann::json& scene_json, const std::filesystem::path& file,
        int frames) {
  const Scene scene = parse_scene(scene_json, file);
  RunOptions options;
  options.frames = frames;
  const RunSummary s = run_scene(scene, options);
  Row r;
  r.experiment = experiment;
  r.integrator = to_string(scene.dynamics->integrator);
  r.solver = scene.solver.linear.kind;
  r.vertices = s.vertices;
  r.elements = s.elements;
  r.frames = static_cast<int>(s.frames.size());
  r.converged = s.all_converged();
  double min_ratio = 1.0, max_penetration = 0.0;
  for (const auto& f : s.frames) {
    r.steps += f.substeps;
    r.newton += f.newton_iterations;
    r.linear += f.linear_iterations;
    r.seconds += f.seconds;
    min_ratio = std::min(min_ratio, f.volume / s.rest_volume);
    max_penetration = std::max(max_penetration, f.max_penetration);
  }
  const auto& last = s.frames.back();
  r.figures = fmt::format("min V/V0 {:.4f}, final V/V0 {:.4f}, max penetration {:.1e} m", min_ratio,
                          last.volume / s.rest_volume, max_penetration);
  return r;
}

// The energy test's setting at bench size: a 1 m cube of 8^3 hexes stretched 20 % along x,
// released at rest with no gravity, damping or contact; one time step of 0.01 s per frame.
Row released_block(DynamicsScheme integrator, int frames) {
  auto disc = std::make_shared<Discretization>(
      box_lattice(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), Eigen::Vector3i::Constant(8)));
  const double E = 1e4, nu = 0.3, mu = E / (2 * (1 + nu)), lambda = E * nu / ((1 + nu) * (1 - 2 * nu));
  auto elastic = std::make_shared<ElasticForm>(disc, std::make_shared<StableNeoHookean>(lambda, mu));
  auto mass = std::make_shared<MassMatrix>(*disc, 1000.0, MassKind::Lumped);
  auto inertia = std::make_shared<InertiaForm>(mass, 0.01);
  Problem problem(disc->mesh().num_vertices());
  problem.add_form(elastic);
  problem.add_form(inertia);
  TimeStepSettings settings;
  settings.integrator = integrator;
  settings.newton.test = ConvergenceTest::Absolute;
  settings.newton.absolute_tolerance = 1e-6;
  TimeStepper stepper(problem, inertia, nullptr, nullptr, {}, disc->mesh().vertices, settings);
  auto linear = make_linear_solver({});
  Eigen::VectorXd x = disc->mesh().rest_positions(), v = Eigen::VectorXd::Zero(x.size());
  for (Eigen::Index i = 0; i < x.size(); i += 3) x(i) *= 1.2;
  const double e0 = elastic->value(x);
  Row r;
  r.experiment = "released block 8x8x8";
  r.integrator = to_string(integrator);
  r.solver = "cholmod";
  r.vertices = disc->mesh().num_vertices();
  r.elements = disc->num_elements();
  r.converged = true;
  const auto t0 = std::chrono::steady_clock::now();
  for (int n = 0; n < frames && r.converged; ++n) {
    const StepStats s = stepper.step(x, v, n, n + 1, *linear);
    r.converged = s.converged;
    r.frames += 1;
    r.steps += 1;
    r.newton += s.newton_iterations;
    r.linear += s.linear_iterations;
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.figures = fmt::format("E_total {:.4g} -> {:.4g} J", e0, elastic->value(x) + mass->kinetic_energy(v));
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Dynamics benchmark: drop test and released pre-stretched block"};
  std::vector<int> sizes = {4, 8, 12};
  int frames = 60, threads = 0;
  app.add_option("--sizes", sizes, "drop test: hexes along the block's width (height is half)")->delimiter(',');
  app.add_option("--frames", frames, "frames per run (the drop test's full sequence is 60)");
  app.add_option("--threads", threads, "TBB threads (0: all)");
  CLI11_PARSE(app, argc, argv);
  std::unique_ptr<tbb::global_control> limit;
  if (threads > 0) limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, threads);
  try {
    const std::filesystem::path file = std::filesystem::path(SINEW_EXAMPLES) / "drop_test.json";
    std::ifstream in(file);
    const nlohmann::json drop = nlohmann::json::parse(in);
    std::vector<Row> rows;
    for (int n : sizes) {
      for (const char* integrator : {"backward_euler", "semi_implicit"}) {
        for (const char* solver : {"cholmod", "pcg"}) {
          nlohmann::json j = drop;
          j["mesh"]["cells"] = {n, n, std::max(1, n / 2)};
          j["dynamics"]["integrator"] = integrator;
          j["solver"]["linear"] = {{"kind", solver}};
          rows.push_back(run(fmt::format("drop {}x{}x{}", n, n, std::max(1, n / 2)), j, file, frames));
          std::fflush(stdout);
        }
      }
    }
    for (const char* integrator : {"backward_euler", "semi_implicit"})
      rows.push_back(released_block(integrator == std::string("backward_euler") ? DynamicsScheme::BackwardEuler
                                                                                : DynamicsScheme::SemiImplicit,
                                    frames));
    std::printf("%-28s %-15s %-8s %7s %7s %6s %6s %9s %8s %9s %7s  %s\n", "experiment", "integrator", "solver",
                "verts", "hexes", "frames", "steps", "ms/frame", "newton/f", "linear/f", "newt/st", "figures");
    for (const auto& r : rows)
      std::printf("%-28s %-15s %-8s %7ld %7ld %6d %6d %9.1f %8.1f %9.1f %7.2f  %s%s\n", r.experiment.c_str(),
                  r.integrator.c_str(), r.solver.c_str(), static_cast<long>(r.vertices), static_cast<long>(r.elements),
                  r.frames, r.steps, 1000.0 * r.seconds / r.frames, double(r.newton) / r.frames,
                  double(r.linear) / r.frames, double(r.newton) / r.steps, r.figures.c_str(),
                  r.converged ? "" : "  (NOT CONVERGED)");
  } catch (const Error& e) {
    std::fprintf(stderr, "dynamics_bench: %s\n", e.what());
    return 2;
  }
  return 0;
}
