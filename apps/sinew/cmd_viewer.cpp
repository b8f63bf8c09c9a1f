// `sinew viewer SCENE.json [--out DIR]`: the browser viewer of a finished run (viewer.html and
// viewer.glb in the run's folder), built from the scene and the run's .vtu frames.
#include <fmt/format.h>
#include <memory>

#include "cli.hpp"
#include "sinew/run/run_viewer.hpp"
#include "sinew/model/scene.hpp"

namespace sinew::cli {

Command add_viewer_command(CLI::App& app) {
  struct Options {
    std::string scene, out, title;
    double fps = 12.0;
    bool quiet = false;
  };
  auto o = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand(
      "viewer", "Write a browser viewer (viewer.html + viewer.glb) of a run's output folder (open it offline)");
  cmd->add_option("scene", o->scene, "the scene file the run used")->required();
  cmd->add_option("--out", o->out, "the run's output folder (default: out/<scene name>)");
  cmd->add_option("--title", o->title, "page title (default: the scene's file name)");
  cmd->add_option("--fps", o->fps, "playback frames per second")->check(CLI::PositiveNumber);
  cmd->add_flag("--quiet", o->quiet, "print nothing on success");
  return {cmd, [o] {
            const Scene scene = load_scene(o->scene);
            const std::filesystem::path out =
                o->out.empty() ? std::filesystem::path("out") / std::filesystem::path(o->scene).stem() : std::filesystem::path(o->out);
            ViewerOptions options;
            if (!o->title.empty()) options.title = o->title;
            options.frames_per_second = o->fps;
            const std::size_t frames = write_run_viewer(scene, out, options);
            if (!o->quiet) fmt::print("viewer of {} frame(s) in {}\n", frames, (out / "viewer.html").string());
          }};
}

}  // namespace sinew::cli
