// `sinew run SCENE.json [--out DIR] [--frames N] [--threads N] [--progress auto|live|plain]
// [--verbose] [--quiet] [--resume] [--checkpoint-seconds S] [--strict] [--viewer]`.
#include "cmd_run.hpp"

#include <algorithm>
#include <chrono>
#include <fmt/format.h>
#include <memory>
#include <new>
#include <tbb/global_control.h>

#include "progress.hpp"
#include "sinew/core/error.hpp"
#include "sinew/run/run_viewer.hpp"
#include "sinew/run/simulation.hpp"

namespace sinew::cli {
namespace {

struct Options {
  std::string scene, out, frames, threads, checkpoint_seconds, progress = "auto";
  bool quiet = false, verbose = false, resume = false, strict = false, viewer = false;
};

void run(const Options& o, int& exit_code) {
  const Scene scene = load_scene(o.scene);
  RunOptions ro;
  ro.out_dir = o.out.empty() ? std::filesystem::path("out") / std::filesystem::path(o.scene).stem() : std::filesystem::path(o.out);
  if (!o.frames.empty()) {
    const long f = parse_integer(o.frames, "--frames");
    if (f < 1 || f > kMaxFrames) throw Error(fmt::format("must be between 1 and {}, got {}", kMaxFrames, f), "--frames");
    ro.frames = static_cast<int>(f);
  }
  std::unique_ptr<tbb::global_control> threads;
  if (!o.threads.empty()) {
    const long t = parse_integer(o.threads, "--threads");
    if (t < 1 || t > 1024) throw Error(fmt::format("must be between 1 and 1024, got {}", t), "--threads");
    threads = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, static_cast<size_t>(t));
  }
  if (!o.checkpoint_seconds.empty()) ro.checkpoint_seconds = parse_number(o.checkpoint_seconds, "--checkpoint-seconds");
  ro.resume = o.resume;
  ro.strict = o.strict;
  if (o.viewer && !scene.output.vtu)
    throw Error("the viewer is built from the run's VTU frames, and this scene has \"output\": {\"vtu\": false}", "--viewer");
  // Energy-limited dynamics (paper 001) has no Newton iterations: it reports its SQP and PGS
  // iteration counters instead.
  const ProgressStyle style = o.quiet ? ProgressStyle::Quiet : progress_style(o.progress, stderr);
  auto printer = std::make_shared<ProgressPrinter>(style, o.verbose && !o.quiet, scene.constraints.has_value());
  if (style != ProgressStyle::Quiet) ro.progress = [printer](const ProgressEvent& e) { (*printer)(e); };
  // Warnings are printed even with --quiet: they are about the answer, not the progress.
  ro.warning = [printer](const std::string& w) {
    printer->clear_line();
    fmt::print(stderr, "sinew: warning: {}\n", w);
  };
  const auto t0 = std::chrono::steady_clock::now();
  RunSummary s;
  try {
    s = run_scene(scene, ro);
  } catch (...) {
    printer->clear_line();  // the error line starts on a clean line
    throw;
  }
  // The browser viewer of every frame written (also of a run that stopped at an unconverged
  // frame: its state is worth a look).
  if (o.viewer && !s.frames.empty()) write_run_viewer(scene, ro.out_dir);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const auto bad = std::find_if(s.frames.begin(), s.frames.end(), [](const FrameRecord& f) { return !f.converged; });
  if (!o.quiet) {
    fmt::print("{} vertices, {} elements, {} frame(s) in {:.2f} s\n", s.vertices, s.elements, s.frames.size(), seconds);
    fmt::print("results in {} ({}{}metrics in summary.json)\n", ro.out_dir.string(),
               scene.output.vtu ? "open simulation.pvd in ParaView; " : "", o.viewer ? "viewer.html in a browser; " : "");
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
  cmd->add_option("--progress", opts->progress,
                  "auto (default: live on a terminal, else plain), live (one line per frame redrawn in place), "
                  "plain (one line per frame)")
      ->check(CLI::IsMember({"auto", "live", "plain"}));
  cmd->add_flag("--verbose", opts->verbose, "also one line per Newton iteration");
  cmd->add_flag("--quiet", opts->quiet, "only errors and warnings (no progress, no results line)");
  cmd->add_flag("--resume", opts->resume, "continue from the output folder's checkpoint");
  cmd->add_option("--checkpoint-seconds", opts->checkpoint_seconds,
                  "wall-clock seconds between checkpoints (default 1; 0: after every frame); the last converged "
                  "frame is always checkpointed");
  cmd->add_flag("--strict", opts->strict, "treat warnings (e.g. a selector taking every vertex) as errors");
  cmd->add_flag("--viewer", opts->viewer, "also write the browser viewer (viewer.html, viewer.glb; docs/viewer.md)");
  return {cmd, [opts, &exit_code] {
            try {
              run(*opts, exit_code);
            } catch (const std::bad_alloc&) {
              // The readers check sizes before allocating; this is the backstop that still
              // names the scene instead of "internal error: std::bad_alloc".
              throw Error("out of memory: the scene (or a file it names) needs more memory than this machine has",
                          opts->scene);
            }
          }};
}

}  // namespace sinew::cli
