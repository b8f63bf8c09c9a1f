// The sinew command line. Every sinew::Error becomes one line on stderr and exit code 2.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <fmt/format.h>

#include "sinew/core/error.hpp"
#include "sinew/version.hpp"

int main(int argc, char** argv) {
  CLI::App app{"Sinew: simulation of hyperelastic solids (flesh, muscle, fat, rubber)"};
  app.set_version_flag("--version", std::string("sinew ") + sinew::kVersion);
  app.require_subcommand(1);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  } catch (const sinew::Error& e) {
    fmt::print(stderr, "sinew: error: {}\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    fmt::print(stderr, "sinew: internal error: {}\n", e.what());
    return 2;
  }
  return 0;
}
