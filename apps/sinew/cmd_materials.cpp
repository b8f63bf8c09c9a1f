// `sinew materials`: every family in the catalog with its parameters (defaults, or normalised
// to a given E and nu, paper 002 §4) and the Lamé parameters, E and nu read off its energy.
#include <fmt/format.h>

#include "cli.hpp"
#include "sinew/core/error.hpp"
#include "sinew/material/catalog.hpp"
#include "sinew/material/lame.hpp"
#include "sinew/material/normalization.hpp"

namespace sinew::cli {

namespace {

struct Options {
  bool json = false;
  std::string E, nu;
  CLI::Option *E_opt = nullptr, *nu_opt = nullptr;
};

struct Row {
  const MaterialInfo* info;
  MaterialParameters parameters;
  std::string domain;
  Lame lame;
  bool has_lame = false, has_ev = false;
  YoungPoisson ev;
  std::string note;
};

Row describe(const MaterialInfo& info, const std::optional<YoungPoisson>& target) {
  Row row{&info, MaterialCatalog::instance().complete(info.name, {}), "", {}, false, false, {}, ""};
  if (target) {
    try {
      if (info.normalized.empty()) {
        row.note = "fixed shape: no parameters to normalise; shown with its own E and nu";
      } else if (info.normalized.size() == 1 && target->nu != 0.0) {
        // lambda_Lame is identically 0: match E at this family's only Poisson ratio, 0.
        row.parameters = normalize(info, {}, YoungPoisson{target->E, 0.0});
        row.note = fmt::format(
            "lambda_Lame is identically 0, so nu = 0 (not {:g}); E matched{}", target->nu,
            info.separable ? fmt::format(". Mix in a volume term for nu != 0 (--mix-mu "
                                         "{} --mix-lambda ...)",
                                         info.name)
                           : "");
      } else {
        row.parameters = normalize(info, {}, *target);
      }
    } catch (const Error& e) {
      row.note = fmt::format("not normalised ({}); shown with its defaults", e.what());
    }
  }
  try {
    const auto material = info.make(row.parameters);
    row.domain = material->domain() == Domain::PositiveJ ? "J > 0" : "all F";
    row.lame = lame_from_energy(*material);
    row.has_lame = true;
    if (row.lame.lambda + row.lame.mu != 0.0) {
      row.ev = young_poisson(row.lame);
      row.has_ev = true;
    }
  } catch (const Error& e) {
    row.note += (row.note.empty() ? "" : "; ") + std::string(e.what());
  }
  return row;
}

nlohmann::json row_json(const Row& row) {
  const MaterialInfo& info = *row.info;
  nlohmann::json params = nlohmann::json::array();
  for (const auto& p : info.parameters) {
    params.push_back({{"key", p.key},
                      {"value", row.parameters.values.at(p.key)},
                      {"default", p.default_value},
                      {"meaning", p.meaning}});
  }
  nlohmann::json functions = nlohmann::json::array();
  for (const auto& f : info.functions) {
    functions.push_back({{"key", f.key},
                         {"expression", row.parameters.functions.at(f.key)},
                         {"default", f.default_expression},
                         {"meaning", f.meaning}});
  }
  nlohmann::json j = {{"name", info.name},
                      {"title", info.title},
                      {"reference", info.reference},
                      {"formula", info.formula},
                      {"parameters", params},
                      {"functions", functions},
                      {"normalized", info.normalized},
                      {"separable", info.separable},
                      {"rest_stable", info.rest_stable},
                      {"domain", row.domain}};
  j["lambda_lame"] = row.has_lame ? nlohmann::json(row.lame.lambda) : nlohmann::json(nullptr);
  j["mu_lame"] = row.has_lame ? nlohmann::json(row.lame.mu) : nlohmann::json(nullptr);
  j["E"] = row.has_ev ? nlohmann::json(row.ev.E) : nlohmann::json(nullptr);
  j["nu"] = row.has_ev ? nlohmann::json(row.ev.nu) : nlohmann::json(nullptr);
  if (!row.note.empty()) j["note"] = row.note;
  return j;
}

std::string row_text(const Row& row) {
  const MaterialInfo& info = *row.info;
  std::string out = fmt::format("{}  ({}; {})\n", info.name, info.title, info.reference);
  out += fmt::format("  psi = {}\n", info.formula);
  out += fmt::format("  parameters: {}\n", format_parameters(row.parameters));
  std::string flags;
  if (!info.normalized.empty()) {
    std::string keys;
    for (const auto& k : info.normalized) keys += (keys.empty() ? "" : ", ") + k;
    flags += "normalised by " + keys;
  }
  if (info.separable) flags += std::string(flags.empty() ? "" : "; ") + "separable (mixable)";
  if (!info.rest_stable) flags += std::string(flags.empty() ? "" : "; ") + "not rest-stable";
  if (!row.domain.empty()) flags += std::string(flags.empty() ? "" : "; ") + "domain " + row.domain;
  if (!flags.empty()) out += fmt::format("  {}\n", flags);
  if (row.has_lame) {
    out += fmt::format("  lambda_Lame = {:.8g}, mu_Lame = {:.8g}", row.lame.lambda, row.lame.mu);
    out += row.has_ev ? fmt::format(", E = {:.8g}, nu = {:.8g}\n", row.ev.E, row.ev.nu)
                      : std::string(" (E, nu undefined)\n");
  }
  if (!row.note.empty()) out += fmt::format("  note: {}\n", row.note);
  return out;
}

}  // namespace

Command add_materials_command(CLI::App& app) {
  auto options = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand(
      "materials",
      "List every material family: parameters (defaults, or normalised to --E/--nu), Lame "
      "parameters, E and nu computed from the energy, reference and formula");
  cmd->add_flag("--json", options->json, "Print JSON");
  options->E_opt =
      cmd->add_option("--E", options->E, "Normalise every family to this Young's modulus");
  options->nu_opt = cmd->add_option("--nu", options->nu, "...and this Poisson's ratio");
  auto run = [options] {
    std::optional<YoungPoisson> target;
    const bool E_given = options->E_opt->count() > 0, nu_given = options->nu_opt->count() > 0;
    if (E_given != nu_given) {
      throw Error(fmt::format("required together with {}", E_given ? "--E" : "--nu"),
                  E_given ? "--nu" : "--E");
    }
    if (E_given) {
      const double E = parse_number(options->E, "--E");
      const double nu = parse_number(options->nu, "--nu");
      if (!(E > 0.0)) throw Error(fmt::format("must be positive, got {}", E), "--E");
      if (!(nu > -1.0 && nu < 0.5)) {
        throw Error(fmt::format("must satisfy -1 < nu < 0.5, got {}", nu), "--nu");
      }
      target = YoungPoisson{E, nu};
    }
    std::vector<Row> rows;
    for (const auto& info : MaterialCatalog::instance().all())
      rows.push_back(describe(info, target));
    if (options->json) {
      nlohmann::json j;
      j["target"] =
          target ? nlohmann::json{{"E", target->E}, {"nu", target->nu}} : nlohmann::json(nullptr);
      j["families"] = nlohmann::json::array();
      for (const auto& row : rows) j["families"].push_back(row_json(row));
      fmt::print("{}\n", j.dump(2));
      return;
    }
    if (target) {
      fmt::print("{} material families, normalised to E = {:g}, nu = {:g}\n\n", rows.size(),
                 target->E, target->nu);
    } else {
      fmt::print("{} material families, default parameters\n\n", rows.size());
    }
    for (const auto& row : rows) fmt::print("{}\n", row_text(row));
  };
  return {cmd, run};
}

}  // namespace sinew::cli
