#pragma once
// A complete description of one material as a user writes it (CLI options, scene files):
// a catalog family with parameters, optionally normalised to (E, nu) (paper 002 §4) and
// given a nonlinearity exponent (§5), or a mix of two families' lambda- and mu-parts (§6).
//
// JSON form (docs/materials.md):
//   {"family": "stable_neo_hookean", "parameters": {"mu": 1, "lambda": 10},
//    "functions": {"f": "log(x)"}, "E": 1e5, "nu": 0.45, "alpha": 2}
//   {"mix": {"lambda_family": "neo_hookean", "mu_family": "linear_corotational",
//            "alpha_lambda": 1, "alpha_mu": 2,
//            "lambda_parameters": {...}, "mu_parameters": {...}},
//    "E": 1e5, "nu": 0.45}
#include <memory>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>

#include "sinew/material/catalog.hpp"
#include "sinew/material/lame.hpp"

namespace sinew {

struct MixSpec {
  std::string lambda_family;
  std::string mu_family;
  double alpha_lambda = 1.0;
  double alpha_mu = 1.0;
  // Non-normalized parameters and functions of each family (its defaults otherwise).
  MaterialParameters lambda_parameters;
  MaterialParameters mu_parameters;
};

struct MaterialSpec {
  std::string family;                  // a catalog name; empty for a mix
  MaterialParameters parameters;       // given values; defaults fill the rest
  std::optional<YoungPoisson> target;  // normalise to (E, nu); required for a mix
  double alpha = 1.0;                  // nonlinearity exponent (Eq. 16); 1 for a mix
  std::optional<MixSpec> mix;
};

// What build_material resolved, for reports (the CLI prints it).
struct BuiltMaterial {
  std::shared_ptr<const Material> material;
  Lame lame;                             // lame_from_energy(*material)
  MaterialParameters parameters;         // single family: complete and normalised
  MaterialParameters lambda_parameters;  // mix: lambda family at (1, 0)
  MaterialParameters mu_parameters;      // mix: mu family at (0, 1)
};

// Validates the combination (family xor mix; a mix needs (E, nu) and takes no top-level
// parameters or alpha; normalized parameters cannot be given together with (E, nu)) and
// builds the material. Errors are sinew::Error naming the offending field.
BuiltMaterial build_material_detailed(const MaterialSpec& spec);
std::shared_ptr<const Material> build_material(const MaterialSpec& spec);

// Strict reader of the JSON form: unknown keys, wrong types, missing fields, non-finite
// numbers, E <= 0, nu outside (-1, 0.5), alpha <= 0, unknown families or parameters are each a
// sinew::Error whose context is `context` followed by the JSON-pointer path of the field
// (context "scene.json: /objects/0/material" -> "scene.json: /objects/0/material/nu"). The
// result is additionally checked by build_material.
MaterialSpec material_spec_from_json(const nlohmann::json& json, const std::string& context);

// The inverse (parameters only where given), e.g. to echo a spec back.
nlohmann::json material_spec_to_json(const MaterialSpec& spec);

}  // namespace sinew
