// `sinew plot OUT_DIR`: PNG/SVG plots of a run folder, drawn by the matplotlib script installed
// beside the executable (scripts/sinew_plot.py, copied to <build>/share/sinew/; docs/plots.md).
// The script reports its own input errors in the CLI's "sinew: error: ..." form; its exit code
// becomes ours.
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fmt/format.h>
#include <filesystem>
#include <spawn.h>
#include <sys/wait.h>
#include <vector>

#include "cli.hpp"
#include "sinew/core/error.hpp"

extern char** environ;

namespace sinew::cli {
namespace {

namespace fs = std::filesystem;

struct Options {
  std::string out_dir, plots, format = "png,svg", only;
};

// The running executable (Linux), for the script beside it and for the material curves.
fs::path self_executable() {
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  if (ec) throw Error(fmt::format("cannot locate the sinew executable: {}", ec.message()), "/proc/self/exe");
  return self;
}

// <dir of sinew>/share/sinew/ (build tree) or <dir of sinew>/../share/sinew/ (an install).
fs::path plot_script(const fs::path& self) {
  const fs::path dir = self.parent_path();
  const fs::path candidates[] = {dir / "share/sinew/sinew_plot.py", dir / "../share/sinew/sinew_plot.py"};
  for (const auto& c : candidates) {
    std::error_code ec;
    if (fs::is_regular_file(c, ec)) return c.lexically_normal();
  }
  throw Error(fmt::format("plot script not found beside the executable (looked for {} and {}); rebuild or reinstall sinew",
                          candidates[0].string(), candidates[1].lexically_normal().string()),
              "sinew plot");
}

int run_plot(const Options& o) {
  const fs::path self = self_executable();
  const fs::path script = plot_script(self);
  // Debian's interpreter, where python3-matplotlib lives; SINEW_PYTHON overrides it.
  const char* env_python = std::getenv("SINEW_PYTHON");
  const std::string python = env_python && *env_python ? env_python : "/usr/bin/python3";
  std::error_code ec;
  if (!fs::is_regular_file(python, ec))
    throw Error(fmt::format("no Python interpreter at {} (install python3-matplotlib, or set SINEW_PYTHON)", python),
                "sinew plot");
  std::vector<std::string> args = {python, script.string(), o.out_dir, "--sinew", self.string(), "--format", o.format};
  if (!o.plots.empty()) args.insert(args.end(), {"--plots", o.plots});
  if (!o.only.empty()) args.insert(args.end(), {"--only", o.only});
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  if (const int err = posix_spawn(&pid, python.c_str(), nullptr, nullptr, argv.data(), environ); err != 0)
    throw Error(fmt::format("cannot start {}: {}", python, std::strerror(err)), "sinew plot");
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) throw Error(fmt::format("waiting for the plot script: {}", std::strerror(errno)), "sinew plot");
  }
  if (WIFSIGNALED(status))
    throw Error(fmt::format("the plot script was killed by signal {}", WTERMSIG(status)), script.string());
  return WEXITSTATUS(status);
}

}  // namespace

Command add_plot_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand(
      "plot", "Plot a run folder (convergence, reactions, volume and min J, energy, stress-stretch) as PNG and SVG");
  cmd->add_option("out_dir", o->out_dir, "output folder of `sinew run` (holds summary.json)")->required();
  cmd->add_option("--plots", o->plots, "where to write the plots (default OUT_DIR/plots)");
  cmd->add_option("--format", o->format, "png, svg or png,svg (default)");
  cmd->add_option("--only", o->only, "comma-separated subset: convergence,reactions,volume,energy,stress_stretch");
  return {cmd, [o, &exit_code] { exit_code = run_plot(*o); }};
}

}  // namespace sinew::cli
