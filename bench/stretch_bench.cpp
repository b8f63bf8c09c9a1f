// Paper 000's stretch test (Fig. 5-6) as a solver benchmark: for each cylinder size and material,
// the time per Newton iteration split into assembly and linear solve, Newton and CG iterations
// per step, peak memory and the final volume change, printed as tables with ratios against the
// smallest size and against stable Neo-Hookean.
//
//   stretch_bench [--sizes 16,33,67] [--models snh,filtered,fixed,corot] [--frames 12]
//                 [--run-frames 67:1,corot@33:5] [--newton-cap 100] [--cg-cap 10000]
//                 [--caps corot:20:1000] [--threads N] [--preconditioners block_jacobi,multigrid,amg]
//                 [--newton default,paper]
//
// Each (size, model) runs in its own child process (this program re-executed with --child), so
// the peak resident memory reported is that run's alone. --run-frames D:K (or MODEL@D:K) runs
// only the first K of the frames at diameter D (the same per-frame motion, a smaller final
// stretch) when the whole test would take too long; --caps MODEL:NEWTON:CG overrides the
// iteration caps for one model (co-rotational does not converge past ~2.4x).
#include <sys/resource.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fmt/format.h>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <tbb/global_control.h>
#include <vector>

#include "sinew/core/error.hpp"
#include "experiments/paper000_experiments.hpp"

namespace {

using namespace sinew;

const std::map<std::string, std::string> kModels = {{"snh", "stable_neo_hookean"},
                                                    {"filtered", "neo_hookean_filtered"},
                                                    {"fixed", "fixed_corotational"},
                                                    {"corot", "corotational"}};

struct Settings {
  int frames = 12;
  int newton_cap = 100;
  int cg_cap = 10000;
  double linear_tolerance = 1e-3;
  int threads = 0;
  std::string preconditioner = "block_jacobi";
  // "default": Sinew's Newton (adaptive projection, predictor); "paper": paper 000's projected
  // Newton (clamped Hessian every iteration, each frame started from the previous one).
  std::string newton = "default";
  bool matrix_free = false;  // "hessian": "matrix_free" (elastic Hessian kept per element)
  bool progress = false;     // print every Newton iteration (large runs)
};

StretchConfig config_for(int diameter, const std::string& family, const Settings& s) {
  StretchConfig c;
  c.family = family;
  c.diameter_cells = diameter;
  c.frames = s.frames;
  c.solver = paper_solver(s.linear_tolerance, s.newton_cap);
  c.solver.linear.max_iterations = s.cg_cap;
  c.solver.linear.preconditioner = s.preconditioner;
  c.solver.linear.matrix_free = s.matrix_free;
  if (s.newton == "paper") {
    c.solver.newton.exact_tail = false;
    c.solver.predictor = LoadStepPredictor::None;
  } else if (s.newton != "default") {
    throw Error("unknown Newton variant '" + s.newton + "' (default, paper)", "--newton");
  }
  return c;
}

double peak_rss_mb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) / 1024.0;  // ru_maxrss is in KiB on Linux
}

// One run, reported as one JSON line on stdout; progress on stderr.
int run_child(int diameter, const std::string& family, int run_frames, const Settings& s) {
  std::unique_ptr<tbb::global_control> threads;
  if (s.threads > 0)
    threads = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, static_cast<size_t>(s.threads));
  ExperimentOptions o;
  o.frames = run_frames;
  o.on_frame = [&](const ExperimentFrame& f) {
    std::fprintf(stderr, "  [D=%d %s] frame %d/%d: %s, %d Newton, %d CG, residual %.2e, %.1f s\n", diameter,
                 family.c_str(), f.frame, run_frames, f.converged ? "converged" : "NOT converged", f.newton_iterations,
                 f.linear_iterations, f.residual, f.seconds);
  };
  const auto start = std::chrono::steady_clock::now();
  if (s.progress)
    o.on_iteration = [&](int frame, const NewtonIterate& it) {
      std::fprintf(stderr, "  [D=%d %s] frame %d, Newton %d: residual %.3e, %.1f s\n", diameter, family.c_str(), frame,
                   it.iteration, it.residual,
                   std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    };
  const ExperimentRun run = run_experiment(stretch_scene(config_for(diameter, family, s)), o);
  nlohmann::json frames = nlohmann::json::array();
  for (const auto& f : run.frames)
    frames.push_back({{"converged", f.converged}, {"newton", f.newton_iterations}, {"cg", f.linear_iterations},
                      {"seconds", f.seconds}, {"assembly", f.assembly_seconds}, {"solve", f.solve_seconds},
                      {"volume", f.volume}, {"min_J", f.min_quadrature_J}});
  const nlohmann::json out = {{"diameter", diameter},
                              {"family", family},
                              {"hexes", run.elements},
                              {"dofs", 3 * run.vertices},
                              {"rest_volume", run.rest_volume},
                              {"frames_total", s.frames},
                              {"frames", frames},
                              {"peak_rss_mb", peak_rss_mb()}};
  std::printf("%s\n", out.dump().c_str());
  return 0;
}

std::vector<std::string> split_list(const std::string& text) {
  std::vector<std::string> v;
  std::stringstream ss(text);
  for (std::string item; std::getline(ss, item, ',');) v.push_back(item);
  return v;
}

std::vector<int> parse_ints(const std::string& text) {
  std::vector<int> v;
  std::stringstream ss(text);
  for (std::string item; std::getline(ss, item, ',');) v.push_back(std::stoi(item));
  return v;
}

struct Row {
  int diameter = 0;
  std::string model, preconditioner;
  long hexes = 0, dofs = 0;
  int frames_run = 0, frames_total = 0, converged = 0;
  long newton = 0, cg = 0;
  int max_newton = 0;
  double seconds = 0, assembly = 0, solve = 0, rss = 0, volume_change = 0, stretch = 0, min_J = 0;
  int newton_cap = 0, cg_cap = 0;
};

Row row_from(const nlohmann::json& j, const std::string& model, double full_stretch) {
  Row r;
  r.diameter = j.at("diameter");
  r.model = model;
  r.hexes = j.at("hexes");
  r.dofs = j.at("dofs");
  r.frames_total = j.at("frames_total");
  for (const auto& f : j.at("frames")) {
    ++r.frames_run;
    r.converged += f.at("converged").get<bool>() ? 1 : 0;
    const int n = f.at("newton");
    r.newton += n;
    r.max_newton = std::max(r.max_newton, n);
    r.cg += f.at("cg").get<long>();
    r.seconds += f.at("seconds").get<double>();
    r.assembly += f.at("assembly").get<double>();
    r.solve += f.at("solve").get<double>();
    r.volume_change = 100.0 * (f.at("volume").get<double>() / j.at("rest_volume").get<double>() - 1.0);
    r.min_J = f.at("min_J");
  }
  r.rss = j.at("peak_rss_mb");
  r.stretch = 1.0 + (full_stretch - 1.0) * r.frames_run / r.frames_total;
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("Paper 000 stretch test as a solver benchmark");
  std::string sizes = "16,33,67", models = "snh,filtered,fixed,corot", run_frames_text, caps_text;
  std::string preconditioners = "block_jacobi";
  Settings s;
  bool child = false;
  int child_diameter = 0, child_run_frames = 0;
  std::string child_family;
  app.add_option("--sizes", sizes, "cylinder diameters in cells (length 1.3x), comma-separated");
  app.add_option("--models", models, "snh, filtered, fixed, corot (comma-separated)");
  app.add_option("--frames", s.frames, "frames for the whole 3.4x stretch");
  app.add_option("--run-frames", run_frames_text, "D:K,... run only the first K frames at diameter D");
  app.add_option("--caps", caps_text, "MODEL:NEWTON:CG,... per-model iteration caps");
  app.add_option("--newton-cap", s.newton_cap, "Newton iterations per frame at most");
  app.add_option("--cg-cap", s.cg_cap, "CG iterations per Newton iteration at most");
  app.add_option("--linear-tolerance", s.linear_tolerance, "relative CG tolerance");
  app.add_option("--threads", s.threads, "worker threads (default: all cores)");
  app.add_option("--preconditioners", preconditioners, "PCG preconditioners to compare (comma-separated)");
  app.add_option("--preconditioner", s.preconditioner)->group("");
  std::string newton_variants = "default";
  app.add_option("--newton", newton_variants,
                 "Newton variants to compare: default (adaptive projection, predictor), paper (clamp, no predictor)");
  app.add_option("--newton-variant", s.newton)->group("");
  app.add_flag("--progress", s.progress, "print every Newton iteration (residual, elapsed time) on stderr");
  app.add_flag("--matrix-free", s.matrix_free,
               "matrix-free Hessian (per-element blocks in single precision; jacobi, block_jacobi or multigrid)");
  app.add_flag("--child", child)->group("");
  app.add_option("--child-diameter", child_diameter)->group("");
  app.add_option("--child-family", child_family)->group("");
  app.add_option("--child-run-frames", child_run_frames)->group("");
  CLI11_PARSE(app, argc, argv);

  try {
    if (child) return run_child(child_diameter, child_family, child_run_frames, s);

    // (model or "", diameter) -> frames to run; model -> (Newton cap, CG cap).
    std::map<std::pair<std::string, int>, int> run_frames;
    std::map<std::string, std::pair<int, int>> caps;
    {
      std::stringstream ss(run_frames_text);
      for (std::string item; std::getline(ss, item, ',');) {
        const auto at = item.find('@'), colon = item.find(':');
        if (colon == std::string::npos) throw Error("expected D:K or MODEL@D:K, got '" + item + "'", "--run-frames");
        const std::string model = at == std::string::npos ? "" : item.substr(0, at);
        const size_t d0 = at == std::string::npos ? 0 : at + 1;
        run_frames[{model, std::stoi(item.substr(d0, colon - d0))}] = std::stoi(item.substr(colon + 1));
      }
    }
    {
      std::stringstream ss(caps_text);
      for (std::string item; std::getline(ss, item, ',');) {
        const auto a = item.find(':'), b = item.rfind(':');
        if (a == std::string::npos || a == b) throw Error("expected MODEL:NEWTON:CG, got '" + item + "'", "--caps");
        caps[item.substr(0, a)] = {std::stoi(item.substr(a + 1, b - a - 1)), std::stoi(item.substr(b + 1))};
      }
    }
    std::vector<std::string> model_keys;
    {
      std::stringstream ss(models);
      for (std::string item; std::getline(ss, item, ',');) {
        if (!kModels.count(item)) throw Error("unknown model '" + item + "' (snh, filtered, fixed, corot)", "--models");
        model_keys.push_back(item);
      }
    }
    const double full_stretch = StretchConfig{}.stretch;
    // popen runs a shell, whose /proc/self/exe is the shell: resolve our own path here.
    const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe");
    std::vector<Row> rows;
    std::vector<std::string> preconditioner_names;
    {
      std::stringstream ss(preconditioners);
      for (std::string item; std::getline(ss, item, ',');) preconditioner_names.push_back(item);
    }
    for (int d : parse_ints(sizes)) {
      for (const auto& key : model_keys)
      for (const auto& pc : preconditioner_names)
      for (const auto& variant : split_list(newton_variants)) {
        int k = s.frames;
        if (run_frames.count({"", d})) k = run_frames[{"", d}];
        if (run_frames.count({key, d})) k = run_frames[{key, d}];
        k = std::min(k, s.frames);
        const auto [newton_cap, cg_cap] = caps.count(key) ? caps[key] : std::make_pair(s.newton_cap, s.cg_cap);
        const std::string cmd = fmt::format(
            "'{}' --child --child-diameter {} --child-family {} --child-run-frames {} --frames {} "
            "--newton-cap {} --cg-cap {} --linear-tolerance {} --threads {} --preconditioner {} --newton-variant {}{}{}",
            self.string(), d, kModels.at(key), k, s.frames, newton_cap, cg_cap, s.linear_tolerance, s.threads, pc,
            variant, s.matrix_free ? " --matrix-free" : "", s.progress ? " --progress" : "");
        std::fprintf(stderr, "running D=%d %s, %s (%d of %d frames)\n", d, kModels.at(key).c_str(), pc.c_str(), k,
                     s.frames);
        FILE* pipe = popen(cmd.c_str(), "r");
        if (!pipe) throw Error("cannot start a child run", cmd);
        std::string text;
        char buffer[4096];
        while (std::fgets(buffer, sizeof buffer, pipe)) text += buffer;
        if (pclose(pipe) != 0 || text.empty()) throw Error("child run failed", cmd);
        rows.push_back(row_from(nlohmann::json::parse(text), key, full_stretch));
        rows.back().newton_cap = newton_cap;
        rows.back().cg_cap = cg_cap;
        rows.back().preconditioner = (variant == "default" ? pc : pc + ", " + variant + " Newton") +
                                     (s.matrix_free ? ", matrix-free" : "");
      }
    }

    // ---- tables
    std::map<std::pair<int, std::string>, const Row*> snh_at;
    std::map<std::string, const Row*> smallest;
    for (const auto& r : rows) {
      if (r.model == "snh") snh_at[{r.diameter, r.preconditioner}] = &r;
      if (!smallest.count(r.model + "/" + r.preconditioner)) smallest[r.model + "/" + r.preconditioner] = &r;
    }
    std::printf("\nStretch benchmark (paper 000 Fig. 5-6): nu = 0.49, E = 1e5, |residual| < 1e-2, PCG (preconditioner "
                "per row), CG tolerance %g, %d frames for 3.4x; threads: %s\n\n",
                s.linear_tolerance, s.frames, s.threads > 0 ? std::to_string(s.threads).c_str() : "all cores");
    std::printf("| D | model | preconditioner | hexes | DOFs | caps (Newton/CG) | frames (conv/run) | stretch | Newton/step (max) | "
                "CG/step | CG/Newton | assembly ms/it | solve ms/it | total s | peak MB | volume %% | min J |\n");
    std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (const auto& r : rows) {
      const double it = std::max<long>(1, r.newton);
      std::printf("| %d | %s | %s | %ld | %ld | %d/%d | %d/%d | %.2f | %.1f (%d) | %.0f | %.0f | %.1f | %.1f | %.1f | %.0f | %+.2f | %.3f |\n",
                  r.diameter, r.model.c_str(), r.preconditioner.c_str(), r.hexes, r.dofs, r.newton_cap, r.cg_cap, r.converged, r.frames_run, r.stretch,
                  static_cast<double>(r.newton) / r.frames_run, r.max_newton, static_cast<double>(r.cg) / r.frames_run,
                  r.cg / it, 1e3 * r.assembly / it, 1e3 * r.solve / it, r.seconds, r.rss, r.volume_change, r.min_J);
    }
    std::printf("\nRatios: CG and time against stable Neo-Hookean at the same size (paper: filtered 0.83x CG, "
                "5.3x time; fixed co-rotational 2.3x CG, 1.43x time); per-DOF cost of a Newton iteration against the "
                "model's smallest size.\n\n");
    std::printf("| D | model | preconditioner | CG / SNH CG | time / SNH time | assembly us/it/DOF | (x smallest) | "
                "solve us/it/DOF | (x smallest) |\n");
    std::printf("|---|---|---|---|---|---|---|---|---|\n");
    for (const auto& r : rows) {
      const Row* base = snh_at.count({r.diameter, r.preconditioner}) ? snh_at[{r.diameter, r.preconditioner}] : nullptr;
      const Row* small = smallest[r.model + "/" + r.preconditioner];
      auto per_dof = [](const Row& x, double t) { return 1e6 * t / std::max<long>(1, x.newton) / x.dofs; };
      const bool same_frames = base && base->frames_run == r.frames_run;
      std::printf("| %d | %s | %s | %s | %s | %.3f | %.2f | %.3f | %.2f |\n", r.diameter, r.model.c_str(), r.preconditioner.c_str(),
                  same_frames ? fmt::format("{:.2f}", static_cast<double>(r.cg) / std::max<long>(1, base->cg)).c_str() : "-",
                  same_frames ? fmt::format("{:.2f}", r.seconds / base->seconds).c_str() : "-", per_dof(r, r.assembly),
                  per_dof(r, r.assembly) / per_dof(*small, small->assembly), per_dof(r, r.solve),
                  per_dof(r, r.solve) / per_dof(*small, small->solve));
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "stretch_bench: error: %s\n", e.what());
    return 2;
  }
}
