#pragma once
// Shared pieces of the sinew command line: strict number parsing (errors name the flag),
// the material-selection options of `material eval` / `material curve`, and JSON/text
// formatting of matrices. Each command lives in its own cmd_*.cpp.
#include <CLI/CLI.hpp>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "sinew/core/types.hpp"
#include "sinew/material/spec.hpp"

namespace sinew::cli {

// A registered subcommand and what to run once it has been parsed.
struct Command {
  CLI::App* app = nullptr;
  std::function<void()> run;
};

Command add_materials_command(CLI::App& app);
Command add_material_eval_command(CLI::App& material);
Command add_material_curve_command(CLI::App& material);
// `sinew viewer SCENE.json`: the browser viewer of a finished run (cmd_viewer.cpp).
Command add_viewer_command(CLI::App& app);
Command add_plot_command(CLI::App& app, int& exit_code);

// A finite number, or sinew::Error("expected a finite number, got '...'", field).
double parse_number(const std::string& text, const std::string& field);
// A whole number, or sinew::Error naming the field.
long parse_integer(const std::string& text, const std::string& field);
// "KEY=VALUE" -> {KEY, VALUE}; sinew::Error naming the field on bad syntax.
std::pair<std::string, std::string> split_key_value(const std::string& text,
                                                    const std::string& field);

// --material, --param, --fn, --E, --nu, --alpha, --mix-lambda, --mix-mu, --alpha-lambda,
// --alpha-mu, or --material-json (a scene's /material object, alone).
struct MaterialOptions {
  std::string material, material_json;
  std::vector<std::string> params, fns;
  std::string E, nu, alpha, mix_lambda, mix_mu, alpha_lambda, alpha_mu;
  CLI::Option *E_opt = nullptr, *nu_opt = nullptr, *alpha_opt = nullptr,
              *alpha_lambda_opt = nullptr, *alpha_mu_opt = nullptr;
};
void add_material_options(CLI::App& cmd, MaterialOptions& options);
// Validates the options (each error names its flag) and returns the spec they describe.
MaterialSpec material_spec_from_options(const MaterialOptions& options);
// Builds it; errors from the library keep their own context (material, parameter, ...).
BuiltMaterial build_from_options(const MaterialOptions& options, MaterialSpec& spec);

// Material description for reports: name, spec, resolved parameters, Lamé, E, nu.
nlohmann::json describe_material(const MaterialSpec& spec, const BuiltMaterial& built);
std::string describe_material_text(const MaterialSpec& spec, const BuiltMaterial& built);
std::string format_parameters(const MaterialParameters& p);

// A matrix as a JSON array of rows, and as aligned text rows.
nlohmann::json rows_json(const Eigen::MatrixXd& m);
// Throws a sinew::Error (context `where`) unless every entry of `values` is finite: a result
// that overflowed (det F = 1e-200) is an error, never a NaN printed with exit code 0.
void require_finite(const Eigen::MatrixXd& values, const std::string& what, const std::string& where);
std::string rows_text(const Eigen::MatrixXd& m, const std::string& indent = "  ");

}  // namespace sinew::cli
