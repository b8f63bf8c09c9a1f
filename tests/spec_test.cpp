// MaterialSpec: building materials from a description, and the strict JSON reader.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>

#include "sinew/core/error.hpp"
#include "sinew/material/catalog.hpp"
#include "sinew/material/lame.hpp"
#include "sinew/material/mixing.hpp"
#include "sinew/material/nonlinearity.hpp"
#include "sinew/material/spec.hpp"

namespace sinew {
namespace {

using nlohmann::json;

// The error's context (where) and message (what), or a failure if none is thrown.
struct Caught {
  std::string context, message;
};
Caught error_of(const std::function<void()>& fn) {
  try {
    fn();
  } catch (const Error& e) {
    return {e.context(), e.message()};
  }
  ADD_FAILURE() << "no sinew::Error thrown";
  return {};
}

TEST(Spec, DefaultsParametersAndNormalisation) {
  MaterialSpec spec;
  spec.family = "linear_corotational";
  BuiltMaterial built = build_material_detailed(spec);
  EXPECT_EQ(built.material->name(), "linear_corotational");
  EXPECT_EQ(built.parameters.values.at("mu"), 1.0);

  spec.parameters.values["mu"] = 2.5;
  built = build_material_detailed(spec);
  EXPECT_NEAR(built.lame.mu, 2.5, 1e-14);

  spec.parameters.values.clear();
  spec.target = YoungPoisson{1e5, 0.45};
  spec.alpha = 2.0;
  built = build_material_detailed(spec);
  const YoungPoisson ev = young_poisson(built.lame);
  EXPECT_NEAR(ev.E, 1e5, 1e-9 * 1e5);
  EXPECT_NEAR(ev.nu, 0.45, 1e-12);
  EXPECT_EQ(built.material->domain(), Domain::PositiveJ);  // alpha = 2
  EXPECT_NE(dynamic_cast<const NonlinearMaterial*>(built.material.get()), nullptr);
}

TEST(Spec, BuildRejectsContradictions) {
  MaterialSpec spec;
  EXPECT_EQ(error_of([&] { build_material(spec); }).context, "material");
  spec.family = "no_such_material";
  EXPECT_EQ(error_of([&] { build_material(spec); }).context, "material");
  spec.family = "linear_corotational";
  spec.target = YoungPoisson{1e5, 0.3};
  spec.parameters.values["mu"] = 1.0;
  EXPECT_EQ(error_of([&] { build_material(spec); }).context,
            "material 'linear_corotational': parameter 'mu'");
  spec.parameters.values.clear();
  spec.alpha = -1.0;
  EXPECT_EQ(error_of([&] { build_material(spec); }).context,
            "material 'linear_corotational': alpha");
  spec.alpha = 1.0;
  spec.target = YoungPoisson{1e5, 0.5};
  EXPECT_EQ(error_of([&] { build_material(spec); }).context, "nu");

  MaterialSpec mix;
  mix.mix = MixSpec{"linear_corotational", "linear_corotational", 1.0, 1.0, {}, {}};
  EXPECT_EQ(error_of([&] { build_material(mix); }).context, "E");  // a mix needs (E, nu)
  mix.target = YoungPoisson{10.0, 0.25};
  mix.alpha = 2.0;
  EXPECT_EQ(error_of([&] { build_material(mix); }).context, "alpha");
}

TEST(Spec, BuildsMixes) {
  MaterialSpec spec;
  spec.mix = MixSpec{"linear_corotational", "linear_corotational", 2.0, 0.5, {}, {}};
  spec.target = YoungPoisson{1e4, 0.3};
  const BuiltMaterial built = build_material_detailed(spec);
  EXPECT_NE(dynamic_cast<const MixedMaterial*>(built.material.get()), nullptr);
  const YoungPoisson ev = young_poisson(built.lame);
  EXPECT_NEAR(ev.E, 1e4, 1e-9 * 1e4);
  EXPECT_NEAR(ev.nu, 0.3, 1e-12);
  EXPECT_NEAR(built.lambda_parameters.values.at("lambda"), 1.0, 1e-14);
  EXPECT_NEAR(built.lambda_parameters.values.at("mu"), 0.0, 1e-14);
  EXPECT_NEAR(built.mu_parameters.values.at("mu"), 1.0, 1e-14);
}

TEST(SpecJson, ReadsBothForms) {
  MaterialSpec spec = material_spec_from_json(
      json::parse(R"({"family": "linear_corotational", "parameters": {"lambda": 4},
                      "alpha": 0.5})"),
      "m");
  EXPECT_EQ(spec.family, "linear_corotational");
  EXPECT_EQ(spec.parameters.values.at("lambda"), 4.0);
  EXPECT_EQ(spec.alpha, 0.5);
  EXPECT_FALSE(spec.target);
  EXPECT_NEAR(lame_from_energy(*build_material(spec)).lambda, 4.0, 1e-13);

  spec = material_spec_from_json(json::parse(R"({"mix": {"lambda_family": "linear_corotational",
                              "mu_family": "linear_corotational", "alpha_mu": 2},
                      "E": 1000, "nu": 0.4})"),
                                 "m");
  ASSERT_TRUE(spec.mix);
  EXPECT_EQ(spec.mix->alpha_mu, 2.0);
  EXPECT_EQ(spec.mix->alpha_lambda, 1.0);
  EXPECT_NEAR(young_poisson(lame_from_energy(*build_material(spec))).nu, 0.4, 1e-12);

  // Round trip through material_spec_to_json.
  const MaterialSpec again = material_spec_from_json(material_spec_to_json(spec), "m");
  EXPECT_EQ(material_spec_to_json(again), material_spec_to_json(spec));
}

TEST(SpecJson, EveryErrorNamesItsPath) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<std::pair<json, std::string>> cases = {
      {json::array(), "scene.json: /materials/0"},
      {json::parse(R"({"family": "linear_corotational", "colour": 1})"),
       "scene.json: /materials/0/colour"},
      {json::parse(R"({"family": 3})"), "scene.json: /materials/0/family"},
      {json::parse(R"({"family": "nonexistent"})"), "scene.json: /materials/0/family"},
      {json::parse(R"({"parameters": {}})"), "scene.json: /materials/0/family"},
      {json::parse(R"({"family": "linear_corotational", "parameters": {"kappa": 1}})"),
       "scene.json: /materials/0/parameters/kappa"},
      {json::parse(R"({"family": "linear_corotational", "parameters": {"mu": "1"}})"),
       "scene.json: /materials/0/parameters/mu"},
      {json::parse(R"({"family": "linear_corotational", "parameters": [1]})"),
       "scene.json: /materials/0/parameters"},
      {json{{"family", "linear_corotational"}, {"parameters", {{"mu", nan}}}},
       "scene.json: /materials/0/parameters/mu"},
      {json::parse(R"({"family": "linear_corotational", "functions": {"f": "x"}})"),
       "scene.json: /materials/0/functions/f"},
      {json::parse(R"({"family": "linear_corotational", "E": 1e5})"),
       "scene.json: /materials/0/nu"},
      {json::parse(R"({"family": "linear_corotational", "nu": 0.3})"),
       "scene.json: /materials/0/E"},
      {json::parse(R"({"family": "linear_corotational", "E": 1e5, "nu": 0.5})"),
       "scene.json: /materials/0/nu"},
      {json::parse(R"({"family": "linear_corotational", "E": 1e5, "nu": 0.7})"),
       "scene.json: /materials/0/nu"},
      {json::parse(R"({"family": "linear_corotational", "E": -1, "nu": 0.3})"),
       "scene.json: /materials/0/E"},
      {json::parse(R"({"family": "linear_corotational", "E": 0, "nu": 0.3})"),
       "scene.json: /materials/0/E"},
      {json{{"family", "linear_corotational"}, {"E", 1.0}, {"nu", nan}},
       "scene.json: /materials/0/nu"},
      {json::parse(R"({"family": "linear_corotational", "E": "1e5", "nu": 0.3})"),
       "scene.json: /materials/0/E"},
      {json::parse(R"({"family": "linear_corotational", "E": 1e5, "nu": 0.3,
                       "parameters": {"mu": 2}})"),
       "scene.json: /materials/0/parameters/mu"},
      {json::parse(R"({"family": "linear_corotational", "alpha": 0})"),
       "scene.json: /materials/0/alpha"},
      {json::parse(R"({"family": "linear_corotational", "alpha": true})"),
       "scene.json: /materials/0/alpha"},
      {json::parse(R"({"mix": {"lambda_family": "linear_corotational",
                              "mu_family": "linear_corotational"}})"),
       "scene.json: /materials/0/E"},
      {json::parse(R"({"family": "linear_corotational", "E": 1, "nu": 0.3,
                       "mix": {"lambda_family": "linear_corotational",
                               "mu_family": "linear_corotational"}})"),
       "scene.json: /materials/0/family"},
      {json::parse(R"({"E": 1, "nu": 0.3, "mix": {"mu_family": "linear_corotational"}})"),
       "scene.json: /materials/0/mix/lambda_family"},
      {json::parse(R"({"E": 1, "nu": 0.3, "mix": {"lambda_family": "linear_corotational",
                       "mu_family": "x"}})"),
       "scene.json: /materials/0/mix/mu_family"},
      {json::parse(R"({"E": 1, "nu": 0.3, "mix": {"lambda_family": "linear_corotational",
                       "mu_family": "linear_corotational", "alpha_mu": -2}})"),
       "scene.json: /materials/0/mix/alpha_mu"},
      {json::parse(R"({"E": 1, "nu": 0.3, "mix": {"lambda_family": "linear_corotational",
                       "mu_family": "linear_corotational", "beta": 1}})"),
       "scene.json: /materials/0/mix/beta"},
      {json::parse(R"({"E": 1, "nu": 0.3, "mix": {"lambda_family": "linear_corotational",
                       "mu_family": "linear_corotational", "mu_parameters": {"mu": 3}}})"),
       "scene.json: /materials/0/mix/mu_parameters/mu"},
      {json::parse(R"({"E": 1, "nu": 0.3, "mix": "linear_corotational"})"),
       "scene.json: /materials/0/mix"},
  };
  for (const auto& item : cases) {
    const json& j = item.first;  // not a structured binding: clang 14 cannot capture one
    SCOPED_TRACE(j.dump());
    const Caught c = error_of([&] { material_spec_from_json(j, "scene.json: /materials/0"); });
    EXPECT_EQ(c.context, item.second) << c.message;
    EXPECT_FALSE(c.message.empty());
  }
}

// Every family in the catalog can be described in JSON with its defaults and built.
TEST(SpecJson, EveryFamilyBuildsFromJson) {
  for (const auto& info : MaterialCatalog::instance().all()) {
    json params = json::object();
    for (const auto& p : info.parameters) params[p.key] = p.default_value;
    const MaterialSpec spec =
        material_spec_from_json(json{{"family", info.name}, {"parameters", params}}, info.name);
    EXPECT_EQ(build_material(spec)->name(), MaterialCatalog::instance().make(info.name)->name());
  }
}

}  // namespace
}  // namespace sinew
