#include "sinew/material/catalog.hpp"

#include <cmath>
#include <fmt/format.h>
#include <set>

#include "sinew/core/error.hpp"

namespace sinew {

MaterialCatalog::MaterialCatalog() {
  register_stable_neo_hookean_families(families_);
  register_isotropic_families(families_);
  std::set<std::string> seen;
  for (const auto& f : families_) {
    if (!seen.insert(f.name).second) throw Error("material registered twice", f.name);
  }
}

const MaterialCatalog& MaterialCatalog::instance() {
  static const MaterialCatalog catalog;
  return catalog;
}

const MaterialInfo& MaterialCatalog::find(const std::string& name) const {
  for (const auto& f : families_) {
    if (f.name == name) return f;
  }
  std::string names;
  for (const auto& f : families_) names += (names.empty() ? "" : ", ") + f.name;
  throw Error(fmt::format("unknown material '{}' (known: {})", name, names), "material");
}

void check_parameter_key(const MaterialInfo& info, const std::string& key, const std::string& context) {
  for (const auto& p : info.parameters)
    if (p.key == key) return;
  std::string keys;
  for (const auto& p : info.parameters) keys += (keys.empty() ? "" : ", ") + p.key;
  throw Error(fmt::format("unknown parameter '{}' of '{}' (expected one of: {})", key, info.name,
                          keys.empty() ? "none" : keys),
              context);
}

void check_function_key(const MaterialInfo& info, const std::string& key, const std::string& context) {
  for (const auto& f : info.functions)
    if (f.key == key) return;
  std::string keys;
  for (const auto& f : info.functions) keys += (keys.empty() ? "" : ", ") + f.key;
  throw Error(fmt::format("unknown function '{}' of '{}' (expected one of: {})", key, info.name,
                          keys.empty() ? "none" : keys),
              context);
}

MaterialParameters complete_parameters(const MaterialInfo& info, const MaterialParameters& given) {
  const std::string where = fmt::format("material '{}'", info.name);
  MaterialParameters out;
  for (const auto& p : info.parameters) out.values[p.key] = p.default_value;
  for (const auto& f : info.functions) out.functions[f.key] = f.default_expression;
  for (const auto& [key, value] : given.values) {
    check_parameter_key(info, key, where);
    if (!std::isfinite(value)) {
      throw Error(fmt::format("parameter '{}' is not a finite number", key), where);
    }
    out.values[key] = value;
  }
  for (const auto& [key, expression] : given.functions) {
    check_function_key(info, key, where);
    out.functions[key] = expression;
  }
  return out;
}

MaterialParameters MaterialCatalog::complete(const std::string& name,
                                             const MaterialParameters& given) const {
  return complete_parameters(find(name), given);
}

std::unique_ptr<Material> MaterialCatalog::make(const std::string& name,
                                                const MaterialParameters& given) const {
  const MaterialInfo& info = find(name);
  const MaterialParameters params = complete(name, given);
  try {
    return info.make(params);
  } catch (const Error& e) {
    throw e.within(fmt::format("material '{}'", name));
  }
}

}  // namespace sinew
