// The sinew command line. Every sinew::Error becomes one line on stderr and exit code 2;
// so does every command-line syntax error. --help and --version exit 0.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <exception>
#include <fmt/format.h>

#include "cli.hpp"
#include "cmd_check.hpp"
#include "cmd_run.hpp"
#include "sinew/core/error.hpp"
#include "sinew/version.hpp"

namespace {

// One line, whatever the message contains.
std::string one_line(std::string text) {
  std::replace(text.begin(), text.end(), '\n', ' ');
  while (!text.empty() && text.back() == ' ') text.pop_back();
  return text;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Sinew: simulation of hyperelastic solids (flesh, muscle, fat, rubber)"};
  app.set_version_flag("--version", std::string("sinew ") + sinew::kVersion);
  app.require_subcommand(1);

  std::vector<sinew::cli::Command> commands;
  int exit_code = 0;  // a command may report a non-error failure (e.g. 3: not converged)
  commands.push_back(sinew::cli::add_run_command(app, exit_code));
  commands.push_back(sinew::cli::add_check_command(app, exit_code));
  commands.push_back(sinew::cli::add_materials_command(app));
  commands.push_back(sinew::cli::add_viewer_command(app));
  CLI::App* material = app.add_subcommand("material", "Evaluate one material: eval, curve");
  material->require_subcommand(1);
  commands.push_back(sinew::cli::add_material_eval_command(*material));
  commands.push_back(sinew::cli::add_material_curve_command(*material));
  commands.push_back(sinew::cli::add_plot_command(app, exit_code));

  try {
    app.parse(argc, argv);
    for (const auto& command : commands) {
      if (command.app->parsed()) command.run();
    }
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    fmt::print(stderr, "sinew: error: {} (see --help)\n", one_line(e.what()));
    return 2;
  } catch (const sinew::Error& e) {
    fmt::print(stderr, "sinew: error: {}\n", one_line(e.what()));
    return 2;
  } catch (const std::exception& e) {
    fmt::print(stderr, "sinew: internal error: {}\n", one_line(e.what()));
    return 2;
  }
  return exit_code;
}
