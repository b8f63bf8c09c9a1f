#include "sinew/material/spec.hpp"

#include <cmath>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <set>

#include "sinew/core/error.hpp"
#include "sinew/material/mixing.hpp"
#include "sinew/material/nonlinearity.hpp"
#include "sinew/material/normalization.hpp"

namespace sinew {

// ---------------------------------------------------------------- building

namespace {

void check_alpha(double alpha, const std::string& field) {
  if (!std::isfinite(alpha) || !(alpha > 0.0)) {
    throw Error(fmt::format("must be a positive finite number, got {}", alpha), field);
  }
}

std::shared_ptr<const Material> make_family(const MaterialInfo& info,
                                            const MaterialParameters& params) {
  try {
    return info.make(params);
  } catch (const Error& e) {
    throw e.within(fmt::format("material '{}'", info.name));
  }
}

}  // namespace

BuiltMaterial build_material_detailed(const MaterialSpec& spec) {
  const MaterialCatalog& catalog = MaterialCatalog::instance();
  BuiltMaterial out;
  if (spec.mix) {
    const MixSpec& mix = *spec.mix;
    if (!spec.family.empty()) throw Error("give either a family or a mix, not both", "family");
    if (!spec.parameters.values.empty() || !spec.parameters.functions.empty()) {
      throw Error("a mix takes its parameters per part (lambda_parameters, mu_parameters)",
                  "parameters");
    }
    if (spec.alpha != 1.0) {
      throw Error("a mix has one exponent per part (alpha_lambda, alpha_mu)", "alpha");
    }
    if (!spec.target) throw Error("a mix needs a target Young's modulus and Poisson's ratio", "E");
    check_alpha(mix.alpha_lambda, "alpha_lambda");
    check_alpha(mix.alpha_mu, "alpha_mu");
    const Lame lame = lame_from_young_poisson(*spec.target);
    MixedParameters parts;
    out.material = make_mixed_material(catalog.find(mix.lambda_family), mix.lambda_parameters,
                                       catalog.find(mix.mu_family), mix.mu_parameters, lame,
                                       mix.alpha_lambda, mix.alpha_mu, &parts);
    out.lambda_parameters = std::move(parts.lambda_part);
    out.mu_parameters = std::move(parts.mu_part);
  } else {
    if (spec.family.empty()) throw Error("no material family given", "material");
    const MaterialInfo& info = catalog.find(spec.family);
    check_alpha(spec.alpha, fmt::format("material '{}': alpha", info.name));
    if (spec.target) {
      for (const auto& key : info.normalized) {
        if (spec.parameters.values.count(key)) {
          throw Error("is set by normalisation to (E, nu); give either it or E and nu",
                      fmt::format("material '{}': parameter '{}'", info.name, key));
        }
      }
      out.parameters = normalize(info, spec.parameters, *spec.target);
    } else {
      out.parameters = catalog.complete(info.name, spec.parameters);
    }
    out.material = make_family(info, out.parameters);
    if (spec.alpha != 1.0) {
      out.material = std::make_shared<const NonlinearMaterial>(out.material, spec.alpha);
    }
  }
  out.lame = lame_from_energy(*out.material);
  return out;
}

std::shared_ptr<const Material> build_material(const MaterialSpec& spec) {
  return build_material_detailed(spec).material;
}

// ---------------------------------------------------------------- JSON

namespace {

using nlohmann::json;

// JSON-pointer paths after the caller's context (e.g. "scene.json: /objects/0/material"), as
// the scene reader writes them.
std::string join(const std::string& context, const std::string& key) { return context + "/" + key; }

void require_object(const json& j, const std::string& path) {
  if (!j.is_object()) {
    throw Error(fmt::format("expected a JSON object, got {}", j.type_name()),
                path.empty() ? "/" : path);
  }
}

void reject_unknown_keys(const json& j, const std::set<std::string>& allowed,
                         const std::string& path) {
  for (const auto& [key, value] : j.items()) {
    if (!allowed.count(key)) {
      std::string names;
      for (const auto& a : allowed) names += (names.empty() ? "" : ", ") + a;
      throw Error(fmt::format("unknown key (expected one of: {})", names), join(path, key));
    }
  }
}

double number(const json& j, const std::string& path) {
  if (!j.is_number()) throw Error(fmt::format("expected a number, got {}", j.type_name()), path);
  const double v = j.get<double>();
  if (!std::isfinite(v)) throw Error("must be a finite number", path);
  return v;
}

std::string text(const json& j, const std::string& path) {
  if (!j.is_string()) throw Error(fmt::format("expected a string, got {}", j.type_name()), path);
  return j.get<std::string>();
}

const MaterialInfo& family_named(const std::string& name, const std::string& path) {
  try {
    return MaterialCatalog::instance().find(name);
  } catch (const Error& e) {
    throw Error(e.message(), path);
  }
}

// {"key": number, ...} checked against the family's parameter list.
void read_parameters(const json& j, const MaterialInfo& info, const std::string& path,
                     MaterialParameters& out) {
  require_object(j, path);
  for (const auto& [key, value] : j.items()) {
    check_parameter_key(info, key, join(path, key));
    out.values[key] = number(value, join(path, key));
  }
}

void read_functions(const json& j, const MaterialInfo& info, const std::string& path,
                    MaterialParameters& out) {
  require_object(j, path);
  for (const auto& [key, value] : j.items()) {
    check_function_key(info, key, join(path, key));
    out.functions[key] = text(value, join(path, key));
  }
}

double exponent(const json& j, const std::string& path) {
  const double alpha = number(j, path);
  if (!(alpha > 0.0)) throw Error(fmt::format("must be positive, got {}", alpha), path);
  return alpha;
}

MixSpec read_mix(const json& j, const std::string& path) {
  require_object(j, path);
  reject_unknown_keys(j,
                      {"lambda_family", "mu_family", "alpha_lambda", "alpha_mu",
                       "lambda_parameters", "mu_parameters", "lambda_functions", "mu_functions"},
                      path);
  MixSpec mix;
  for (const char* key : {"lambda_family", "mu_family"}) {
    if (!j.contains(key)) throw Error("missing required key", join(path, key));
  }
  mix.lambda_family = text(j.at("lambda_family"), join(path, "lambda_family"));
  mix.mu_family = text(j.at("mu_family"), join(path, "mu_family"));
  const MaterialInfo& lambda_info = family_named(mix.lambda_family, join(path, "lambda_family"));
  const MaterialInfo& mu_info = family_named(mix.mu_family, join(path, "mu_family"));
  if (j.contains("alpha_lambda"))
    mix.alpha_lambda = exponent(j["alpha_lambda"], join(path, "alpha_lambda"));
  if (j.contains("alpha_mu")) mix.alpha_mu = exponent(j["alpha_mu"], join(path, "alpha_mu"));
  for (const auto& [info, which, params] :
       {std::tuple{&lambda_info, std::string("lambda"), &mix.lambda_parameters},
        std::tuple{&mu_info, std::string("mu"), &mix.mu_parameters}}) {
    const std::string pkey = which + "_parameters", fkey = which + "_functions";
    if (j.contains(pkey)) read_parameters(j[pkey], *info, join(path, pkey), *params);
    if (j.contains(fkey)) read_functions(j[fkey], *info, join(path, fkey), *params);
    for (const auto& key : info->normalized) {
      if (params->values.count(key)) {
        throw Error("is set by the mix (the part is normalised to unit Lame parameters)",
                    join(join(path, pkey), key));
      }
    }
  }
  return mix;
}

}  // namespace

MaterialSpec material_spec_from_json(const json& j, const std::string& context) {
  require_object(j, context);
  reject_unknown_keys(j, {"family", "parameters", "functions", "E", "nu", "alpha", "mix"}, context);
  MaterialSpec spec;

  // (E, nu): both or neither; Eq. 15's ranges.
  if (j.contains("E") != j.contains("nu")) {
    const char* missing = j.contains("E") ? "nu" : "E";
    throw Error(fmt::format("missing: E and nu are given together"), join(context, missing));
  }
  if (j.contains("E")) {
    const double E = number(j["E"], join(context, "E"));
    const double nu = number(j["nu"], join(context, "nu"));
    if (!(E > 0.0)) throw Error(fmt::format("must be positive, got {}", E), join(context, "E"));
    if (!(nu > -1.0 && nu < 0.5)) {
      throw Error(fmt::format("must satisfy -1 < nu < 0.5, got {}", nu), join(context, "nu"));
    }
    spec.target = YoungPoisson{E, nu};
  }
  if (j.contains("alpha")) spec.alpha = exponent(j["alpha"], join(context, "alpha"));

  if (j.contains("mix")) {
    for (const char* key : {"family", "parameters", "functions", "alpha"}) {
      if (j.contains(key)) {
        throw Error(
            "not allowed together with 'mix' (a mix sets its parts' parameters and "
            "exponents inside 'mix')",
            join(context, key));
      }
    }
    if (!spec.target) throw Error("missing: a mix needs E and nu", join(context, "E"));
    spec.mix = read_mix(j["mix"], join(context, "mix"));
    return spec;
  }

  if (!j.contains("family"))
    throw Error("missing required key (or give 'mix')", join(context, "family"));
  spec.family = text(j["family"], join(context, "family"));
  const MaterialInfo& info = family_named(spec.family, join(context, "family"));
  if (j.contains("parameters")) {
    read_parameters(j["parameters"], info, join(context, "parameters"), spec.parameters);
  }
  if (j.contains("functions")) {
    read_functions(j["functions"], info, join(context, "functions"), spec.parameters);
  }
  if (spec.target) {
    for (const auto& key : info.normalized) {
      if (spec.parameters.values.count(key)) {
        throw Error("is set by normalisation to (E, nu); give either it or E and nu",
                    join(join(context, "parameters"), key));
      }
    }
  }
  return spec;
}

json material_spec_to_json(const MaterialSpec& spec) {
  json j = json::object();
  auto params_json = [](const MaterialParameters& p, json& target, const std::string& values_key,
                        const std::string& functions_key) {
    if (!p.values.empty()) target[values_key] = p.values;
    if (!p.functions.empty()) target[functions_key] = p.functions;
  };
  if (spec.mix) {
    const MixSpec& m = *spec.mix;
    json mix = {{"lambda_family", m.lambda_family},
                {"mu_family", m.mu_family},
                {"alpha_lambda", m.alpha_lambda},
                {"alpha_mu", m.alpha_mu}};
    params_json(m.lambda_parameters, mix, "lambda_parameters", "lambda_functions");
    params_json(m.mu_parameters, mix, "mu_parameters", "mu_functions");
    j["mix"] = mix;
  } else {
    j["family"] = spec.family;
    params_json(spec.parameters, j, "parameters", "functions");
    if (spec.alpha != 1.0) j["alpha"] = spec.alpha;
  }
  if (spec.target) {
    j["E"] = spec.target->E;
    j["nu"] = spec.target->nu;
  }
  return j;
}

}  // namespace sinew
