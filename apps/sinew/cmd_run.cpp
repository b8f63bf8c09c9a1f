// `sinew run SCENE.json [--out DIR] [--frames N] [--threads N] [--quiet] [--resume]`.
#include "cmd_run.hpp"

#include <algorithm>
#include <chrono>
#include <fmt/format.h>
#include <memory>
#include <tbb/global_control.h>
#include <unistd.h>

#include "sinew/core/error.hpp"
#include "sinew/run/simulation.hpp"

namespace sinew::cli {
namespace {

struct Options {
  std::string scene, out, frames, threads;
  bool quiet = false, resume = false;
};

void run(const Options& o, int& exit_code) {
  const Scene scene = load_scene(o.scene);
  RunOptions ro;
  ro.out_dir = o.out.empty() ? std::filesystem::path("out") / std::filesystem::path(o.scene).stem() : std::filesystem::path(o.out);
  if (!o.frames.empty()) {
    const long f = parse_integer(o.frames, "--frames");
    if (f < 1 || f > 1000000) throw Error(fmt::format("must be between 1 and 1000000, got {}", f), "--frames");
    ro.frames = static_cast<int>(f);
  }
  std::unique_ptr<tbb::global_control> threads;
  if (!o.threads.empty()) {
    const long t = parse_integer(o.threads, "--threads");
    if (t < 1 || t > 1024) throw Error(fmt::format("must be between 1 and 1024, got {}", t), "--threads");
    threads = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, static_cast<size_t>(t));
  }
  ro.resume = o.resume;
  const bool tty = isatty(STDERR_FILENO);
  if (!o.quiet) {
    // Energy-limited dynamics (paper 001) has no Newton iterations: it reports its SQP and PGS
    // iteration counters instead.
    const bool sqp = scene.constraints.has_value();
    ro.progress = [tty, sqp](const ProgressEvent& e) {
      if (e.frame_done) {
        const FrameRecord& r = *e.record;
        if (tty) fmt::print(stderr, "\r\033[K");
        const double outer = sqp ? r.counter("sqp_iterations") : r.newton_iterations;
        const double inner = sqp ? r.counter("pgs_iterations") : r.linear_iterations;
        fmt::print(stderr, "frame {}/{}: {} {}, {} {} iterations, residual {:.3e}, volume {:.6g}, {:.2f} s{}\n", e.frame,
                   e.frames, outer, sqp ? "SQP" : "Newton", inner, sqp ? "PGS" : "linear", r.residual, r.volume,
                   r.seconds, r.converged ? "" : "  NOT CONVERGED: " + r.failure);
      } else if (tty) {
        fmt::print(stderr, "\r\033[Kframe {}/{}  Newton {}  residual {:.3e}  elapsed {:.1f} s", e.frame, e.frames,
                   e.newton_iteration, e.residual, e.elapsed);
      } else if (e.newton_iteration > 0) {
        fmt::print(stderr, "frame {}/{} Newton {} residual {:.3e} elapsed {:.1f} s\n", e.frame, e.frames,
                   e.newton_iteration, e.residual, e.elapsed);
      }
    };
  }
  const auto t0 = std::chrono::steady_clock::now();
  RunSummary s;
  try {
    s = run_scene(scene, ro);
  } catch (...) {
    if (tty && !o.quiet) fmt::print(stderr, "\r\033[K");  // clear the live line for the error line
    throw;
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const auto bad = std::find_if(s.frames.begin(), s.frames.end(), [](const FrameRecord& f) { return !f.converged; });
  if (!o.quiet) {
    fmt::print("{} vertices, {} elements, {} frame(s) in {:.2f} s\n", s.vertices, s.elements, s.frames.size(), seconds);
    fmt::print("results in {} ({}metrics in summary.json)\n", ro.out_dir.string(),
               scene.output.vtu ? "open simulation.pvd in ParaView; " : "");
  }
  if (bad != s.frames.end()) {
    fmt::print(stderr, "sinew: frame {} did not converge: {}; the run stopped there (see {})\n", bad->frame,
               bad->failure, (ro.out_dir / "summary.json").string());
    exit_code = 3;
  }
}

}  // namespace

Command add_run_command(CLI::App& app, int& exit_code) {
  auto opts = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand("run", "Simulate a scene file (JSON, see docs/scene-format.md)");
  cmd->add_option("scene", opts->scene, "scene file")->required();
  cmd->add_option("--out", opts->out, "output folder (default: out/<scene name>)");
  cmd->add_option("--frames", opts->frames, "number of frames (overrides the scene)");
  cmd->add_option("--threads", opts->threads, "worker threads (default: all cores)");
  cmd->add_flag("--quiet", opts->quiet, "no progress output");
  cmd->add_flag("--resume", opts->resume, "continue from the output folder's checkpoint");
  return {cmd, [opts, &exit_code] { run(*opts, exit_code); }};
}

}  // namespace sinew::cli
