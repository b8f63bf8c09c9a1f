#pragma once
#include "cli.hpp"

namespace sinew::cli {
// `sinew run SCENE.json`: simulate a scene (exit 3 if a frame did not converge).
Command add_run_command(CLI::App& app, int& exit_code);
}  // namespace sinew::cli
