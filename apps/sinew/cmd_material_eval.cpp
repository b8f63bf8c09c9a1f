// `sinew material eval`: psi, P, the Hessian, its projection and eigenvalues at one F.
#include <algorithm>
#include <fmt/format.h>

#include "cli.hpp"
#include "sinew/core/error.hpp"

namespace sinew::cli {

namespace {

struct Options {
  MaterialOptions material;
  std::vector<std::string> F;
  std::string projection = "clamp";
  bool json = false;
};

Mat3 parse_F(const std::vector<std::string>& values) {
  if (values.size() != 9) {
    throw Error(fmt::format("expected 9 values (F row by row: f00 f01 f02 f10 ... f22), got {}",
                            values.size()),
                "--F");
  }
  Mat3 F;
  for (int k = 0; k < 9; ++k) {
    F(k / 3, k % 3) = parse_number(values[static_cast<std::size_t>(k)],
                                   fmt::format("--F entry f{}{}", k / 3, k % 3));
  }
  return F;
}

}  // namespace

Command add_material_eval_command(CLI::App& material) {
  auto o = std::make_shared<Options>();
  CLI::App* cmd = material.add_subcommand(
      "eval",
      "Evaluate psi, P = dpsi/dF, the 9x9 Hessian (column-wise vec), its PSD "
      "projection and eigenvalues at one deformation gradient");
  add_material_options(*cmd, o->material);
  cmd->add_option("--F", o->F, "Deformation gradient, 9 numbers row by row")->required();
  cmd->add_option("--projection", o->projection, "Hessian projection: clamp (default), abs, none");
  cmd->add_flag("--json", o->json, "Print JSON");
  auto run = [o] {
    Projection projection;
    try {
      projection = parse_projection(o->projection);
    } catch (const Error& e) {
      throw Error(e.message(), "--projection");
    }
    const Mat3 F = parse_F(o->F);
    MaterialSpec spec;
    const BuiltMaterial built = build_from_options(o->material, spec);
    const Material& m = *built.material;

    Evaluation e;
    Mat9 H;
    Eigensystem es;
    try {
      e = m.evaluate(F, projection);
      H = m.hessian(F);
      es = m.eigensystem(F);
    } catch (const Error& err) {
      throw err.within("--F");
    }
    Vec9 eigenvalues = es.values;
    std::sort(eigenvalues.data(), eigenvalues.data() + 9);
    const std::string at = fmt::format("--F (J = {:.6g})", F.determinant());
    require_finite(Eigen::Matrix<double, 1, 1>(F.determinant()), "J = det F", at);
    require_finite(Eigen::Matrix<double, 1, 1>(e.psi), "psi", at);
    require_finite(e.P, "P", at);
    require_finite(H, "the Hessian", at);
    require_finite(e.hessian, "the projected Hessian", at);
    require_finite(eigenvalues, "a Hessian eigenvalue", at);

    if (o->json) {
      nlohmann::json j;
      j["material"] = describe_material(spec, built);
      j["F"] = rows_json(F);
      j["J"] = F.determinant();
      j["projection"] = to_string(projection);
      j["psi"] = e.psi;
      j["P"] = rows_json(e.P);
      j["hessian"] = rows_json(H);
      j["projected_hessian"] = rows_json(e.hessian);
      j["eigenvalues"] = std::vector<double>(eigenvalues.data(), eigenvalues.data() + 9);
      fmt::print("{}\n", j.dump(2));
      return;
    }
    fmt::print("{}", describe_material_text(spec, built));
    fmt::print("F (rows), J = {:.10g}:\n{}", F.determinant(), rows_text(F));
    fmt::print("psi = {:.17g}\n", e.psi);
    fmt::print("P = dpsi/dF (rows):\n{}", rows_text(e.P));
    fmt::print("Hessian d2psi/dF2 (9x9, column-wise vec):\n{}", rows_text(H));
    fmt::print("projected Hessian ({}):\n{}", to_string(projection), rows_text(e.hessian));
    fmt::print("Hessian eigenvalues (ascending):\n{}", rows_text(eigenvalues.transpose()));
  };
  return {cmd, run};
}

}  // namespace sinew::cli
