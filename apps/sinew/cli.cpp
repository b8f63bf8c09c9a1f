#include "cli.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fmt/format.h>

#include "sinew/core/error.hpp"
#include "sinew/material/catalog.hpp"
#include "sinew/material/lame.hpp"

namespace sinew::cli {

double parse_number(const std::string& text, const std::string& field) {
  const char* begin = text.c_str();
  char* end = nullptr;
  errno = 0;
  const double value = std::strtod(begin, &end);
  if (text.empty() || end != begin + text.size()) {
    throw Error(fmt::format("expected a number, got '{}'", text), field);
  }
  if (!std::isfinite(value) || errno == ERANGE) {
    throw Error(fmt::format("expected a finite number, got '{}'", text), field);
  }
  return value;
}

long parse_integer(const std::string& text, const std::string& field) {
  const char* begin = text.c_str();
  char* end = nullptr;
  errno = 0;
  const long value = std::strtol(begin, &end, 10);
  if (text.empty() || end != begin + text.size() || errno == ERANGE) {
    throw Error(fmt::format("expected a whole number, got '{}'", text), field);
  }
  return value;
}

std::pair<std::string, std::string> split_key_value(const std::string& text,
                                                    const std::string& field) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == text.size()) {
    throw Error(fmt::format("expected KEY=VALUE, got '{}'", text), field);
  }
  return {text.substr(0, eq), text.substr(eq + 1)};
}

void add_material_options(CLI::App& cmd, MaterialOptions& o) {
  cmd.add_option("--material", o.material, "Material family (see `sinew materials`)");
  cmd.add_option("--material-json", o.material_json,
                 "The whole material as JSON, as in a scene's /material (docs/materials.md)");
  cmd.add_option("--param", o.params, "Family parameter KEY=VALUE (repeatable)");
  cmd.add_option("--fn", o.fns, "Family function KEY=EXPR in x (repeatable)");
  o.E_opt = cmd.add_option("--E", o.E, "Normalise to this Young's modulus (with --nu)");
  o.nu_opt = cmd.add_option("--nu", o.nu, "Normalise to this Poisson's ratio (with --E)");
  o.alpha_opt = cmd.add_option("--alpha", o.alpha, "Nonlinearity exponent (paper 002 Eq. 16)");
  cmd.add_option("--mix-lambda", o.mix_lambda, "Mix: family giving the lambda-part (Eq. 19)");
  cmd.add_option("--mix-mu", o.mix_mu, "Mix: family giving the mu-part (Eq. 19)");
  o.alpha_lambda_opt =
      cmd.add_option("--alpha-lambda", o.alpha_lambda, "Mix: exponent of the lambda-part (Eq. 20)");
  o.alpha_mu_opt =
      cmd.add_option("--alpha-mu", o.alpha_mu, "Mix: exponent of the mu-part (Eq. 20)");
}

namespace {

const MaterialInfo& family_for_flag(const std::string& name, const std::string& flag) {
  try {
    return MaterialCatalog::instance().find(name);
  } catch (const Error& e) {
    throw Error(e.message(), flag);
  }
}

void check_positive(double value, const std::string& flag) {
  if (!(value > 0.0)) throw Error(fmt::format("must be positive, got {}", value), flag);
}

}  // namespace

MaterialSpec material_spec_from_options(const MaterialOptions& o) {
  if (!o.material_json.empty()) {
    const bool others = !o.material.empty() || !o.params.empty() || !o.fns.empty() || !o.mix_lambda.empty() ||
                        !o.mix_mu.empty() || !o.E.empty() || !o.nu.empty() || !o.alpha.empty() ||
                        !o.alpha_lambda.empty() || !o.alpha_mu.empty();
    if (others) throw Error("describes the whole material; give it without the other material flags", "--material-json");
    nlohmann::json j;
    try {
      j = nlohmann::json::parse(o.material_json);
    } catch (const nlohmann::json::parse_error& e) {
      throw Error(fmt::format("malformed JSON: {}", e.what()), "--material-json");
    }
    return material_spec_from_json(j, "--material-json");
  }
  MaterialSpec spec;
  const bool E_given = o.E_opt && o.E_opt->count() > 0;
  const bool nu_given = o.nu_opt && o.nu_opt->count() > 0;
  if (E_given != nu_given) {
    throw Error(fmt::format("required together with {}", E_given ? "--E" : "--nu"),
                E_given ? "--nu" : "--E");
  }
  if (E_given) {
    const double E = parse_number(o.E, "--E");
    const double nu = parse_number(o.nu, "--nu");
    check_positive(E, "--E");
    if (!(nu > -1.0 && nu < 0.5)) {
      throw Error(fmt::format("must satisfy -1 < nu < 0.5, got {}", nu), "--nu");
    }
    spec.target = YoungPoisson{E, nu};
  }

  const bool mixing = !o.mix_lambda.empty() || !o.mix_mu.empty();
  if (mixing) {
    if (o.mix_lambda.empty()) throw Error("required together with --mix-mu", "--mix-lambda");
    if (o.mix_mu.empty()) throw Error("required together with --mix-lambda", "--mix-mu");
    if (!o.material.empty())
      throw Error("give either --material or --mix-lambda/--mix-mu", "--material");
    if (!o.params.empty() || !o.fns.empty()) {
      throw Error("a mix normalises both parts itself; it takes no --param/--fn", "--param");
    }
    if (o.alpha_opt && o.alpha_opt->count()) {
      throw Error("a mix takes --alpha-lambda and --alpha-mu instead", "--alpha");
    }
    if (!spec.target) throw Error("a mix needs --E and --nu", "--E");
    MixSpec mix;
    mix.lambda_family = family_for_flag(o.mix_lambda, "--mix-lambda").name;
    mix.mu_family = family_for_flag(o.mix_mu, "--mix-mu").name;
    if (o.alpha_lambda_opt && o.alpha_lambda_opt->count()) {
      mix.alpha_lambda = parse_number(o.alpha_lambda, "--alpha-lambda");
      check_positive(mix.alpha_lambda, "--alpha-lambda");
    }
    if (o.alpha_mu_opt && o.alpha_mu_opt->count()) {
      mix.alpha_mu = parse_number(o.alpha_mu, "--alpha-mu");
      check_positive(mix.alpha_mu, "--alpha-mu");
    }
    spec.mix = mix;
    return spec;
  }

  if ((o.alpha_lambda_opt && o.alpha_lambda_opt->count()) ||
      (o.alpha_mu_opt && o.alpha_mu_opt->count())) {
    throw Error("only with --mix-lambda and --mix-mu",
                o.alpha_lambda_opt->count() ? "--alpha-lambda" : "--alpha-mu");
  }
  if (o.material.empty()) throw Error("required (or --mix-lambda and --mix-mu)", "--material");
  const MaterialInfo& info = family_for_flag(o.material, "--material");
  spec.family = info.name;
  for (const auto& text : o.params) {
    const auto [key, value] = split_key_value(text, "--param");
    const std::string flag = "--param " + key;
    check_parameter_key(info, key, flag);
    if (spec.parameters.values.count(key)) throw Error("given twice", flag);
    spec.parameters.values[key] = parse_number(value, flag);
  }
  for (const auto& text : o.fns) {
    const auto [key, expression] = split_key_value(text, "--fn");
    const std::string flag = "--fn " + key;
    check_function_key(info, key, flag);
    if (spec.parameters.functions.count(key)) throw Error("given twice", flag);
    spec.parameters.functions[key] = expression;
  }
  if (spec.target) {
    for (const auto& key : info.normalized) {
      if (spec.parameters.values.count(key)) {
        throw Error("is set by normalisation to --E/--nu; give either it or --E and --nu",
                    "--param " + key);
      }
    }
  }
  if (o.alpha_opt && o.alpha_opt->count()) {
    spec.alpha = parse_number(o.alpha, "--alpha");
    check_positive(spec.alpha, "--alpha");
  }
  return spec;
}

BuiltMaterial build_from_options(const MaterialOptions& options, MaterialSpec& spec) {
  spec = material_spec_from_options(options);
  return build_material_detailed(spec);
}

std::string format_parameters(const MaterialParameters& p) {
  std::string out;
  for (const auto& [key, value] : p.values) {
    out += fmt::format("{}{} = {:.10g}", out.empty() ? "" : ", ", key, value);
  }
  for (const auto& [key, expression] : p.functions) {
    out += fmt::format("{}{}(x) = {}", out.empty() ? "" : ", ", key, expression);
  }
  return out.empty() ? "(none)" : out;
}

namespace {

nlohmann::json parameters_json(const MaterialParameters& p) {
  nlohmann::json j = nlohmann::json::object();
  for (const auto& [key, value] : p.values) j[key] = value;
  nlohmann::json out = {{"values", j}};
  if (!p.functions.empty()) out["functions"] = p.functions;
  return out;
}

}  // namespace

nlohmann::json describe_material(const MaterialSpec& spec, const BuiltMaterial& built) {
  nlohmann::json j;
  j["name"] = built.material->name();
  j["spec"] = material_spec_to_json(spec);
  j["domain"] = built.material->domain() == Domain::PositiveJ ? "J > 0" : "all F";
  if (spec.mix) {
    j["lambda_part_parameters"] = parameters_json(built.lambda_parameters);
    j["mu_part_parameters"] = parameters_json(built.mu_parameters);
  } else {
    j["parameters"] = parameters_json(built.parameters);
  }
  j["lame"] = {{"lambda", built.lame.lambda}, {"mu", built.lame.mu}};
  try {
    const YoungPoisson ev = young_poisson(built.lame);
    j["E"] = ev.E;
    j["nu"] = ev.nu;
  } catch (const Error&) {  // lambda + mu = 0: undefined, reported as null
    j["E"] = nullptr;
    j["nu"] = nullptr;
  }
  return j;
}

std::string describe_material_text(const MaterialSpec& spec, const BuiltMaterial& built) {
  std::string out = fmt::format("material: {}\n", built.material->name());
  if (spec.mix) {
    out += fmt::format("  lambda-part ({}) at (1, 0): {}\n", spec.mix->lambda_family,
                       format_parameters(built.lambda_parameters));
    out += fmt::format("  mu-part ({}) at (0, 1): {}\n", spec.mix->mu_family,
                       format_parameters(built.mu_parameters));
  } else {
    out += fmt::format("  parameters: {}\n", format_parameters(built.parameters));
  }
  out +=
      fmt::format("  lambda_Lame = {:.10g}, mu_Lame = {:.10g}", built.lame.lambda, built.lame.mu);
  try {
    const YoungPoisson ev = young_poisson(built.lame);
    out += fmt::format(", E = {:.10g}, nu = {:.10g}\n", ev.E, ev.nu);
  } catch (const Error&) {
    out += " (E, nu undefined: lambda + mu = 0)\n";
  }
  out += fmt::format("  domain: {}\n",
                     built.material->domain() == Domain::PositiveJ ? "J > 0" : "all F");
  return out;
}

void require_finite(const Eigen::MatrixXd& values, const std::string& what, const std::string& where) {
  if (values.allFinite()) return;
  throw Error(fmt::format("{} is not finite here (the material's formulas overflow or are undefined at this "
                          "deformation)",
                          what),
              where);
}

nlohmann::json rows_json(const Eigen::MatrixXd& m) {
  nlohmann::json rows = nlohmann::json::array();
  for (Eigen::Index r = 0; r < m.rows(); ++r) {
    nlohmann::json row = nlohmann::json::array();
    for (Eigen::Index c = 0; c < m.cols(); ++c) row.push_back(m(r, c));
    rows.push_back(row);
  }
  return rows;
}

std::string rows_text(const Eigen::MatrixXd& m, const std::string& indent) {
  std::string out;
  for (Eigen::Index r = 0; r < m.rows(); ++r) {
    out += indent;
    for (Eigen::Index c = 0; c < m.cols(); ++c) out += fmt::format(" {:>17.10g}", m(r, c));
    out += "\n";
  }
  return out;
}

}  // namespace sinew::cli
