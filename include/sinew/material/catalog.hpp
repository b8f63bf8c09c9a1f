#pragma once
// The catalog of material families: names, parameters (the papers' symbols in ASCII),
// which parameters normalisation solves for, and a factory. CLI and scene files build
// materials only through here, so every family is validated the same way.
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "sinew/material/material.hpp"

namespace sinew {

struct ParameterSpec {
  std::string key;
  double default_value = 0.0;
  std::string meaning;
};

// A user-supplied scalar function (Hill's f, Valanis-Landel's f, g, h): an expression in x
// that may use the family's numeric parameters (see material/expression.hpp).
struct FunctionSpec {
  std::string key;
  std::string default_expression;
  std::string meaning;
};

struct MaterialParameters {
  std::map<std::string, double> values;
  std::map<std::string, std::string> functions;
};

struct MaterialInfo {
  std::string name;       // snake_case CLI name
  std::string title;      // human name
  std::string reference;  // e.g. "paper 000 Eq. 14"
  std::string formula;    // the energy as plain text, for listings and docs
  std::vector<ParameterSpec> parameters;
  std::vector<FunctionSpec> functions;
  // Parameters solved when the family is set from (E, nu): two, or one for families whose
  // lambda_Lame is identically zero (they can only match E, at nu = 0). Empty: fixed shape.
  std::vector<std::string> normalized;
  // Psi is linear in (lambda_Lame, mu_Lame) once normalised, so its lambda- and mu-parts can
  // be mixed with another family's (paper 002 Eq. 19-20).
  bool separable = false;
  // P(I) = 0.
  bool rest_stable = true;
  // Receives a complete, validated parameter set (defaults filled in).
  std::function<std::unique_ptr<Material>(const MaterialParameters&)> make;
};

class MaterialCatalog {
 public:
  static const MaterialCatalog& instance();

  const std::vector<MaterialInfo>& all() const { return families_; }
  const MaterialInfo& find(const std::string& name) const;  // throws Error naming the choices

  // Fills defaults for missing keys; rejects unknown keys and non-finite values.
  MaterialParameters complete(const std::string& name, const MaterialParameters& given) const;
  std::unique_ptr<Material> make(const std::string& name,
                                 const MaterialParameters& given = {}) const;

 private:
  MaterialCatalog();
  std::vector<MaterialInfo> families_;
};

// Throw sinew::Error (with `context`) listing the family's keys if `key` is not one of them.
void check_parameter_key(const MaterialInfo& info, const std::string& key, const std::string& context);
void check_function_key(const MaterialInfo& info, const std::string& key, const std::string& context);

// The family's defaults with `given` applied: rejects unknown keys and non-finite values.
MaterialParameters complete_parameters(const MaterialInfo& info, const MaterialParameters& given);

// Registration, one function per group of families (each in its own source file).
void register_stable_neo_hookean_families(std::vector<MaterialInfo>& out);
void register_isotropic_families(std::vector<MaterialInfo>& out);

}  // namespace sinew
