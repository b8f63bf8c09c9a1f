// Mixing lambda- and mu-parts of separable families (paper 002 §6, Eq. 19-20).
#include <gtest/gtest.h>

#include <cmath>

#include "material_battery.hpp"
#include "sinew/core/error.hpp"
#include "sinew/material/catalog.hpp"
#include "sinew/material/families/corotational.hpp"
#include "sinew/material/mixing.hpp"
#include "sinew/material/nonlinearity.hpp"
#include "sinew/material/normalization.hpp"

namespace sinew {
namespace {

const MaterialInfo* find_family(const std::string& name) {
  for (const auto& f : MaterialCatalog::instance().all()) {
    if (f.name == name) return &f;
  }
  return nullptr;
}

std::vector<std::string> separable_names(bool need_volume) {
  std::vector<std::string> names;
  for (const auto& f : MaterialCatalog::instance().all()) {
    if (f.separable && (!need_volume || f.normalized.size() == 2)) names.push_back(f.name);
  }
  return names;
}

std::vector<test::SampleF> positive_samples(unsigned seed) {
  return test::sample_set(seed, 4, false);
}

class MixSeparableFamily : public ::testing::TestWithParam<std::string> {};

// Eq. 19: the family normalised to (lambda_L, mu_L) equals lambda_L psi_lambda + mu_L psi_mu.
TEST_P(MixSeparableFamily, SplitsIntoLambdaAndMuParts) {
  const MaterialInfo& info = MaterialCatalog::instance().find(GetParam());
  const auto mu_part = info.make(mu_part_parameters(info));
  const bool has_volume = info.normalized.size() == 2;
  const auto lambda_part = has_volume ? info.make(lambda_part_parameters(info)) : nullptr;
  for (const Lame lame : {Lame{10.0, 1.0}, Lame{2.0e4, 3.5e2}, Lame{0.0, 1.0}}) {
    if (!has_volume && lame.lambda != 0.0) continue;
    const auto whole = info.make(normalize(info, {}, lame));
    for (const auto& s : positive_samples(17u)) {
      SCOPED_TRACE(test::describe(s));
      double psi = lame.mu * mu_part->psi(s.F);
      Mat3 P = lame.mu * mu_part->pk1(s.F);
      Mat9 H = lame.mu * mu_part->hessian(s.F);
      if (lambda_part) {
        psi += lame.lambda * lambda_part->psi(s.F);
        P += lame.lambda * lambda_part->pk1(s.F);
        H += lame.lambda * lambda_part->hessian(s.F);
      }
      const double w = std::abs(lame.lambda) + lame.mu;
      EXPECT_NEAR(whole->psi(s.F), psi, 1e-10 * std::max(w, std::abs(psi)));
      EXPECT_LE((whole->pk1(s.F) - P).norm(), 1e-10 * std::max(w, P.norm()));
      EXPECT_LE((whole->hessian(s.F) - H).norm(), 1e-9 * std::max(w, H.norm()));
    }
  }
}

// The mix's Lamé parameters are the requested ones for every pair of parts and exponents.
TEST_P(MixSeparableFamily, MixesWithEveryOtherFamilyAtTheRequestedLameParameters) {
  const MaterialInfo& mu_family = MaterialCatalog::instance().find(GetParam());
  for (const auto& lambda_name : separable_names(true)) {
    const MaterialInfo& lambda_family = MaterialCatalog::instance().find(lambda_name);
    for (const auto& [a1, a2] : {std::pair{1.0, 1.0}, std::pair{2.0, 0.5}, std::pair{0.5, 3.0}}) {
      SCOPED_TRACE(lambda_name + " + " + GetParam());
      const Lame target{4.5e4, 3.4e3};
      const auto mix = make_mixed_material(lambda_family, {}, mu_family, {}, target, a1, a2);
      const Lame got = lame_from_energy(*mix);
      EXPECT_NEAR(got.lambda, target.lambda, 1e-9 * target.lambda);
      EXPECT_NEAR(got.mu, target.mu, 1e-9 * target.lambda);
      EXPECT_LE(mix->pk1(Mat3::Identity()).norm(), 1e-9 * target.lambda);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Catalog, MixSeparableFamily, ::testing::ValuesIn(separable_names(false)),
                         [](const auto& p) { return p.param; });

// Eq. 20 spelled out for linear corotational parts: the mix with exponents (a1, a2) is
//   lambda_L/(2 a1^2) (sum s^a1 - 3)^2 + mu_L/a2^2 sum (s^a2 - 1)^2.
TEST(Mixing, Eq20ForLinearCorotationalParts) {
  const MaterialInfo& lc = MaterialCatalog::instance().find("linear_corotational");
  const Lame lame{7.0, 2.0};
  const double a1 = 2.0, a2 = 0.5;
  const auto mix = make_mixed_material(lc, {}, lc, {}, lame, a1, a2);
  EXPECT_EQ(mix->domain(), Domain::PositiveJ);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.3, 2.0);
  for (int n = 0; n < 20; ++n) {
    const Vec3 s(u(rng), u(rng), u(rng));
    const double v = s.array().pow(a1).sum() - 3.0;
    const double expected = lame.lambda / (2.0 * a1 * a1) * v * v +
                            lame.mu / (a2 * a2) * (s.array().pow(a2) - 1.0).square().sum();
    EXPECT_NEAR(mix->psi_stretch(s), expected, 1e-12 * std::max(1.0, expected));
  }
}

TEST(Mixing, FiniteDifferenceBatteryOnMixes) {
  const MaterialInfo& lc = MaterialCatalog::instance().find("linear_corotational");
  // Always available: linear corotational's own parts with different exponents.
  test::check_material_battery(*make_mixed_material(lc, {}, lc, {}, {8.0, 1.5}, 2.0, 0.5));
  test::check_material_battery(*make_mixed_material(lc, {}, lc, {}, {8.0, 1.5}, 1.0, 1.0));
  // The paper's example: corotational shear with a Neo-Hookean volume term.
  for (const char* volume : {"neo_hookean_ogden", "neo_hookean", "stable_neo_hookean"}) {
    const MaterialInfo* info = find_family(volume);
    if (!info || !info->separable) continue;
    SCOPED_TRACE(std::string("lambda-part of ") + volume);
    test::check_material_battery(*make_mixed_material(*info, {}, lc, {}, {8.0, 1.5}, 1.0, 1.0));
    test::check_material_battery(*make_mixed_material(*info, {}, lc, {}, {8.0, 1.5}, 0.5, 2.0));
  }
}

TEST(Mixing, LinearCorotationalMixAtUnitExponentsIsLinearCorotational) {
  const MaterialInfo& lc = MaterialCatalog::instance().find("linear_corotational");
  const auto mix = make_mixed_material(lc, {}, lc, {}, {3.0, 0.4});
  const LinearCorotational reference(3.0, 0.4);
  for (const auto& s : test::sample_set(8u, 3, true)) {
    EXPECT_NEAR(mix->psi(s.F), reference.psi(s.F), 1e-12 * std::max(1.0, reference.psi(s.F)));
    EXPECT_LE((mix->pk1(s.F) - reference.pk1(s.F)).norm(),
              1e-12 * std::max(1.0, reference.pk1(s.F).norm()));
  }
  EXPECT_EQ(mix->domain(), Domain::All);
}

MaterialInfo custom(std::string name, bool separable, std::vector<std::string> normalized) {
  MaterialInfo info;
  info.name = std::move(name);
  info.separable = separable;
  info.normalized = normalized;
  for (const auto& key : normalized) info.parameters.push_back({key, 1.0, ""});
  info.make = [normalized](const MaterialParameters& p) -> std::unique_ptr<Material> {
    const double lambda = normalized.size() == 2 ? p.values.at("lambda") : 0.0;
    return std::make_unique<LinearCorotational>(lambda, p.values.at("mu"));
  };
  return info;
}

TEST(Mixing, RejectsNonSeparableAndShearOnlyLambdaParts) {
  const MaterialInfo& lc = MaterialCatalog::instance().find("linear_corotational");
  const MaterialInfo coupled = custom("coupled", false, {"lambda", "mu"});
  try {
    make_mixed_material(coupled, {}, lc, {}, {1.0, 1.0});
    ADD_FAILURE() << "non-separable lambda-part accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("not separable"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("'coupled'"), std::string::npos) << e.what();
  }
  EXPECT_THROW(make_mixed_material(lc, {}, coupled, {}, {1.0, 1.0}), Error);

  const MaterialInfo shear_only = custom("shear_only", true, {"mu"});
  EXPECT_THROW(make_mixed_material(shear_only, {}, lc, {}, {1.0, 1.0}), Error);
  // ...but a shear-only family is a fine mu-part (paper 002 §6: give it volume preservation).
  const auto mix = make_mixed_material(lc, {}, shear_only, {}, {5.0, 1.0});
  const Lame got = lame_from_energy(*mix);
  EXPECT_NEAR(got.lambda, 5.0, 1e-12);
  EXPECT_NEAR(got.mu, 1.0, 1e-12);
}

TEST(Mixing, ConstructorChecksThePartsAndExponents) {
  const auto unit_lambda = std::make_shared<LinearCorotational>(1.0, 0.0);
  const auto unit_mu = std::make_shared<LinearCorotational>(0.0, 1.0);
  EXPECT_NO_THROW(MixedMaterial(unit_lambda, unit_mu, {1.0, 1.0}));
  EXPECT_THROW(MixedMaterial(unit_mu, unit_mu, {1.0, 1.0}), Error);
  EXPECT_THROW(
      MixedMaterial(unit_lambda, std::make_shared<LinearCorotational>(0.0, 2.0), {1.0, 1.0}),
      Error);
  EXPECT_THROW(MixedMaterial(unit_lambda, unit_mu, {1.0, 1.0}, 0.0, 1.0), Error);
  EXPECT_THROW(MixedMaterial(unit_lambda, unit_mu, {1.0, 1.0}, 1.0, -2.0), Error);
  EXPECT_THROW(MixedMaterial(nullptr, unit_mu, {1.0, 1.0}), Error);
}

}  // namespace
}  // namespace sinew
