// Normalisation to a target (E, nu) (paper 002 §4, Eq. 14-15), for every catalog family.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "sinew/core/error.hpp"
#include "sinew/material/catalog.hpp"
#include "sinew/material/families/corotational.hpp"
#include "sinew/material/normalization.hpp"

namespace sinew {
namespace {

std::vector<std::string> all_names() {
  std::vector<std::string> names;
  for (const auto& f : MaterialCatalog::instance().all()) names.push_back(f.name);
  return names;
}

const MaterialInfo* find_family(const std::string& name) {
  for (const auto& f : MaterialCatalog::instance().all()) {
    if (f.name == name) return &f;
  }
  return nullptr;
}

std::string error_of(const std::function<void()>& fn) {
  try {
    fn();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

// A linear corotational material whose parameters are mapped through `lame` first: lets the
// tests build families with one, two, nonlinear or degenerate parameterisations.
MaterialInfo synthetic(std::string name, std::vector<ParameterSpec> params,
                       std::vector<std::string> normalized,
                       std::function<Lame(const MaterialParameters&)> lame) {
  MaterialInfo info;
  info.name = std::move(name);
  info.parameters = std::move(params);
  info.normalized = std::move(normalized);
  info.separable = true;
  info.make = [lame](const MaterialParameters& p) -> std::unique_ptr<Material> {
    const Lame l = lame(p);
    return std::make_unique<LinearCorotational>(l.lambda, l.mu);
  };
  return info;
}

class NormalizeEveryFamily : public ::testing::TestWithParam<std::string> {};

TEST_P(NormalizeEveryFamily, RoundTripsYoungsModulusAndPoissonsRatio) {
  const MaterialInfo& info = MaterialCatalog::instance().find(GetParam());
  const MaterialParameters defaults = MaterialCatalog::instance().complete(info.name, {});
  for (double E : {1e3, 1e5, 1e7}) {
    for (double nu : {0.49, 0.45, 0.3, 0.0}) {
      SCOPED_TRACE(testing::Message() << "E = " << E << ", nu = " << nu);
      if (info.normalized.empty()) {
        EXPECT_THROW(normalize(info, {}, YoungPoisson{E, nu}), Error);
        continue;
      }
      if (info.normalized.size() == 1 && nu != 0.0) {
        const std::string message = error_of([&] { normalize(info, {}, YoungPoisson{E, nu}); });
        EXPECT_NE(message.find("nu = 0"), std::string::npos) << message;
        EXPECT_NE(message.find("mix"), std::string::npos) << message;
        continue;
      }
      const MaterialParameters p = normalize(info, {}, YoungPoisson{E, nu});
      const YoungPoisson got = young_poisson(lame_from_energy(*info.make(p)));
      EXPECT_NEAR(got.E, E, 1e-9 * E);
      EXPECT_NEAR(got.nu, nu, 1e-9 * std::max(std::abs(nu), 1e-2));
      // Only the normalized parameters move.
      for (const auto& [key, value] : defaults.values) {
        const bool solved =
            std::find(info.normalized.begin(), info.normalized.end(), key) != info.normalized.end();
        if (!solved) {
          EXPECT_EQ(p.values.at(key), value) << key;
        }
      }
      EXPECT_EQ(p.functions, defaults.functions);
    }
  }
}

TEST_P(NormalizeEveryFamily, NormalisingToItsOwnLameParametersIsTheIdentity) {
  const MaterialInfo& info = MaterialCatalog::instance().find(GetParam());
  if (info.normalized.empty()) GTEST_SKIP() << "no normalized parameters";
  const MaterialParameters defaults = MaterialCatalog::instance().complete(info.name, {});
  const Lame own = lame_from_energy(*info.make(defaults));
  const MaterialParameters p = normalize(info, {}, own);
  for (const auto& key : info.normalized) {
    EXPECT_NEAR(p.values.at(key), defaults.values.at(key),
                1e-9 * std::max(1.0, std::abs(defaults.values.at(key))))
        << key;
  }
}

INSTANTIATE_TEST_SUITE_P(Catalog, NormalizeEveryFamily, ::testing::ValuesIn(all_names()),
                         [](const auto& p) { return p.param; });

// Paper 000 §3.4: for Eq. 14, mu = 4/3 mu_L and lambda = lambda_L + 5/6 mu_L.
TEST(Normalize, StableNeoHookeanMatchesPaper000) {
  const MaterialInfo* info = find_family("stable_neo_hookean");
  if (!info) GTEST_SKIP() << "stable_neo_hookean not in this catalog";
  for (const Lame target : {Lame{10.0, 1.0}, Lame{3.4e5, 1.2e4}, Lame{0.0, 2.0}}) {
    const MaterialParameters p = normalize(*info, {}, target);
    EXPECT_NEAR(p.values.at("mu"), 4.0 / 3.0 * target.mu, 1e-12 * target.mu * 4.0 / 3.0);
    EXPECT_NEAR(p.values.at("lambda"), target.lambda + 5.0 / 6.0 * target.mu,
                1e-12 * (target.lambda + target.mu));
  }
}

// Paper 000 §3.4 (and paper 002 Table 1, Eq. 13 of Smith et al.): mu = mu_L, lambda = lambda_L +
// mu_L.
TEST(Normalize, StableNeoHookeanEq13MatchesPaper000) {
  const MaterialInfo* info = find_family("stable_neo_hookean_eq13");
  if (!info) GTEST_SKIP() << "stable_neo_hookean_eq13 not in this catalog";
  for (const Lame target : {Lame{10.0, 1.0}, Lame{3.4e5, 1.2e4}, Lame{0.0, 2.0}}) {
    const MaterialParameters p = normalize(*info, {}, target);
    EXPECT_NEAR(p.values.at("mu"), target.mu, 1e-12 * target.mu);
    EXPECT_NEAR(p.values.at("lambda"), target.lambda + target.mu,
                1e-12 * (target.lambda + target.mu));
  }
}

TEST(Normalize, LinearCorotationalIsItsOwnLinearisation) {
  const MaterialInfo& info = MaterialCatalog::instance().find("linear_corotational");
  const MaterialParameters p = normalize(info, {}, Lame{7.5, 0.25});
  EXPECT_NEAR(p.values.at("lambda"), 7.5, 1e-13);
  EXPECT_NEAR(p.values.at("mu"), 0.25, 1e-14);
  // Eq. 15 by hand: E = 1e5, nu = 0.45.
  const MaterialParameters q = normalize(info, {}, YoungPoisson{1e5, 0.45});
  EXPECT_NEAR(q.values.at("lambda"), 1e5 * 0.45 / (1.45 * 0.1), 1e-8);
  EXPECT_NEAR(q.values.at("mu"), 1e5 / 2.9, 1e-9);
}

TEST(Normalize, NonlinearParameterisationConvergesByNewton) {
  // lambda_L = a^3 + b, mu_L = exp(b): not affine, Newton needs several steps.
  const MaterialInfo info = synthetic("cubic", {{"a", 1.0, ""}, {"b", 0.0, ""}}, {"a", "b"},
                                      [](const MaterialParameters& p) {
                                        const double a = p.values.at("a"), b = p.values.at("b");
                                        return Lame{a * a * a + b, std::exp(b)};
                                      });
  const Lame target{20.0, 3.0};
  const MaterialParameters p = normalize(info, {}, target);
  const Lame got = lame_from_energy(*info.make(p));
  EXPECT_NEAR(got.lambda, 20.0, 1e-12 * 20.0);
  EXPECT_NEAR(got.mu, 3.0, 1e-12 * 3.0);
  EXPECT_NEAR(p.values.at("b"), std::log(3.0), 1e-12);
}

TEST(Normalize, OneParameterFamilyMatchesEAtNuZeroOnly) {
  const MaterialInfo info =
      synthetic("shear_only", {{"mu", 1.0, ""}}, {"mu"}, [](const MaterialParameters& p) {
        return Lame{0.0, 0.5 * p.values.at("mu")};
      });
  const MaterialParameters p = normalize(info, {}, YoungPoisson{300.0, 0.0});
  EXPECT_NEAR(p.values.at("mu"), 300.0, 1e-10);  // E = 2 mu_L = mu
  const std::string message = error_of([&] { normalize(info, {}, YoungPoisson{300.0, 0.3}); });
  EXPECT_NE(message.find("material 'shear_only'"), std::string::npos) << message;
  EXPECT_NE(message.find("only match nu = 0"), std::string::npos) << message;
  EXPECT_NE(message.find("paper 002 §6"), std::string::npos) << message;
}

TEST(Normalize, OneParameterFamilyWithHiddenVolumeTermIsCaught) {
  // Listed with one normalized parameter but lambda_L = 1 always: normalisation must not
  // silently return a material with the wrong lambda_Lame.
  const MaterialInfo info =
      synthetic("wrong_listing", {{"mu", 1.0, ""}}, {"mu"}, [](const MaterialParameters& p) {
        return Lame{1.0, p.values.at("mu")};
      });
  EXPECT_THROW(normalize(info, {}, Lame{0.0, 2.0}), Error);
}

TEST(Normalize, SingularJacobianIsAnError) {
  // Both parameters only scale mu_L: (lambda_L, mu_L) cannot be set independently.
  const MaterialInfo info = synthetic("degenerate", {{"a", 1.0, ""}, {"b", 1.0, ""}}, {"a", "b"},
                                      [](const MaterialParameters& p) {
                                        return Lame{0.0, p.values.at("a") + p.values.at("b")};
                                      });
  const std::string message = error_of([&] { normalize(info, {}, Lame{1.0, 1.0}); });
  EXPECT_NE(message.find("singular"), std::string::npos) << message;
  EXPECT_NE(message.find("material 'degenerate'"), std::string::npos) << message;
}

TEST(Normalize, UnreachableTargetIsAnError) {
  // mu_L = exp(b) > 0 can never reach mu_L = -1: Newton must give up with an error.
  const MaterialInfo info = synthetic("positive", {{"a", 1.0, ""}, {"b", 0.0, ""}}, {"a", "b"},
                                      [](const MaterialParameters& p) {
                                        return Lame{p.values.at("a"), std::exp(p.values.at("b"))};
                                      });
  EXPECT_THROW(normalize(info, {}, Lame{1.0, -1.0}), Error);
}

TEST(Normalize, FamilyWithoutNormalizedParametersIsAnError) {
  const MaterialInfo info = synthetic("fixed", {}, {}, [](const MaterialParameters&) {
    return Lame{0.0, 1.0};
  });
  const std::string message = error_of([&] { normalize(info, {}, Lame{0.0, 1.0}); });
  EXPECT_NE(message.find("no parameters to normalise"), std::string::npos) << message;
}

TEST(Normalize, RejectsBadBaseParametersAndTargets) {
  const MaterialInfo& info = MaterialCatalog::instance().find("linear_corotational");
  MaterialParameters bad;
  bad.values["kappa"] = 1.0;
  EXPECT_THROW(normalize(info, bad, Lame{1.0, 1.0}), Error);
  EXPECT_THROW(normalize(info, {}, Lame{std::nan(""), 1.0}), Error);
  EXPECT_THROW(normalize(info, {}, Lame{0.0, 0.0}), Error);
}

// ---------------------------------------------------------------- E, nu <-> Lamé (Eq. 14-15)

TEST(YoungPoisson, RoundTrip) {
  for (double E : {1e-3, 1.0, 1e5, 1e9}) {
    for (double nu : {-0.9, -0.3, 0.0, 0.25, 0.45, 0.499}) {
      const YoungPoisson back = young_poisson(lame_from_young_poisson({E, nu}));
      EXPECT_NEAR(back.E, E, 1e-12 * E);
      EXPECT_NEAR(back.nu, nu, 1e-12);
    }
  }
  const Lame l = lame_from_young_poisson({1.0, 0.25});  // lambda = mu = 0.4
  EXPECT_NEAR(l.lambda, 0.4, 1e-15);
  EXPECT_NEAR(l.mu, 0.4, 1e-15);
}

TEST(YoungPoisson, InvalidInputsNameTheField) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (double nu : {0.5, 0.7, -1.0, -2.0, nan, inf}) {
    try {
      lame_from_young_poisson({1.0, nu});
      ADD_FAILURE() << "nu = " << nu << " accepted";
    } catch (const Error& e) {
      EXPECT_EQ(e.context(), "nu") << e.what();
    }
  }
  for (double E : {0.0, -1.0, nan, inf, -inf}) {
    try {
      lame_from_young_poisson({E, 0.3});
      ADD_FAILURE() << "E = " << E << " accepted";
    } catch (const Error& e) {
      EXPECT_EQ(e.context(), "E") << e.what();
    }
  }
  EXPECT_THROW(young_poisson(Lame{1.0, -1.0}), Error);  // lambda + mu = 0
}

}  // namespace
}  // namespace sinew
