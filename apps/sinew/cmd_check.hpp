#pragma once
#include "cli.hpp"

namespace sinew::cli {
// `sinew check SCENE.json`: each energy term's derivatives against finite differences at a state
// of the scene (exit 3 if a term fails).
Command add_check_command(CLI::App& app, int& exit_code);
}  // namespace sinew::cli
