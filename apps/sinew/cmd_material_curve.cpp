// `sinew material curve`: the stress-stretch curve of one homogeneous deformation.
#include <fmt/format.h>

#include "cli.hpp"
#include "sinew/core/error.hpp"
#include "sinew/material/curve.hpp"

namespace sinew::cli {

namespace {

struct Options {
  MaterialOptions material;
  std::string from = "0.5", to = "2", steps = "30", mode = "uniaxial";
  bool csv = false, json = false;
};

}  // namespace

Command add_material_curve_command(CLI::App& material) {
  auto o = std::make_shared<Options>();
  CLI::App* cmd = material.add_subcommand(
      "curve",
      "Stress-stretch curve: uniaxial F = diag(s, t, t) and biaxial diag(s, s, t) with "
      "the lateral stretch t solved for zero lateral stress, or simple shear "
      "F = I + s e0 e1^T; prints stretch, lateral stretch, J, nominal stress (P00, or "
      "P01 for shear) and psi");
  add_material_options(*cmd, o->material);
  cmd->add_option("--stretch-from", o->from, "First stretch s (default 0.5)");
  cmd->add_option("--stretch-to", o->to, "Last stretch s (default 2)");
  cmd->add_option("--steps", o->steps, "Number of intervals, >= 1 (default 30)");
  cmd->add_option("--mode", o->mode, "uniaxial (default), biaxial or shear");
  cmd->add_flag("--csv", o->csv, "Print CSV");
  cmd->add_flag("--json", o->json, "Print JSON");
  auto run = [o] {
    CurveMode mode;
    try {
      mode = parse_curve_mode(o->mode);
    } catch (const Error& e) {
      throw Error(e.message(), "--mode");
    }
    const double from = parse_number(o->from, "--stretch-from");
    const double to = parse_number(o->to, "--stretch-to");
    const long steps = parse_integer(o->steps, "--steps");
    if (steps < 1 || steps > 1000000) {
      throw Error(fmt::format("must be between 1 and 1000000, got {}", steps), "--steps");
    }
    if (!(from < to)) {
      throw Error(fmt::format("must be smaller than --stretch-to ({:g}), got {:g}", to, from),
                  "--stretch-from");
    }
    if (mode != CurveMode::Shear && !(from > 0.0)) {
      throw Error(fmt::format("a principal stretch must be positive in {} mode, got {:g}",
                              to_string(mode), from),
                  "--stretch-from");
    }
    if (o->csv && o->json) throw Error("give at most one of --csv and --json", "--csv");
    MaterialSpec spec;
    const BuiltMaterial built = build_from_options(o->material, spec);
    const auto curve =
        stress_stretch_curve(*built.material, mode, from, to, static_cast<int>(steps));
    const char* stress_name = mode == CurveMode::Shear ? "P01" : "P00";
    for (const auto& p : curve)
      require_finite(Eigen::Vector4d(p.lateral, p.J, p.stress, p.psi), "the stress, energy or lateral stretch",
                     fmt::format("--stretch-from/--stretch-to (at stretch {:.6g})", p.stretch));
    if (o->json) {
      nlohmann::json j;
      j["material"] = describe_material(spec, built);
      j["mode"] = to_string(mode);
      j["stress_component"] = stress_name;
      nlohmann::json points = nlohmann::json::array();
      for (const auto& p : curve) {
        points.push_back({{"stretch", p.stretch},
                          {"lateral_stretch", p.lateral},
                          {"J", p.J},
                          {"stress", p.stress},
                          {"psi", p.psi}});
      }
      j["points"] = points;
      fmt::print("{}\n", j.dump(2));
      return;
    }
    if (o->csv) {
      fmt::print("stretch,lateral_stretch,J,stress,psi\n");
      for (const auto& p : curve) {
        fmt::print("{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}\n", p.stretch, p.lateral, p.J, p.stress,
                   p.psi);
      }
      return;
    }
    fmt::print("{}", describe_material_text(spec, built));
    fmt::print("{} curve, nominal stress {}\n", to_string(mode), stress_name);
    fmt::print("{:>14} {:>14} {:>14} {:>16} {:>16}\n", "stretch", "lateral", "J", "stress", "psi");
    for (const auto& p : curve) {
      fmt::print("{:>14.8g} {:>14.8g} {:>14.8g} {:>16.8g} {:>16.8g}\n", p.stretch, p.lateral, p.J,
                 p.stress, p.psi);
    }
  };
  return {cmd, run};
}

}  // namespace sinew::cli
