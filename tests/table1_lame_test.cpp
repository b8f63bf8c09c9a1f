// Paper 002 Table 1, Lame columns: for every family, the Lame parameters read off the energy
// (Eq. 3-4, lame_from_energy) equal the table's formula, written here independently, at the
// defaults and at random parameter sets; and the analytic stretch Hessian at rest equals
// finite differences of the energy, so "read off the energy" really is the energy's.
#include <gtest/gtest.h>

#include <fmt/format.h>
#include <functional>
#include <random>

#include "sinew/core/error.hpp"
#include "sinew/core/finite_difference.hpp"
#include "sinew/material/catalog.hpp"
#include "sinew/material/lame.hpp"

namespace sinew {
namespace {

using Params = MaterialParameters;
using TableLame = std::function<Lame(const Params&)>;
using Randomizer = std::function<Params(std::mt19937&)>;

double uniform(std::mt19937& rng, double a, double b) {
  return std::uniform_real_distribution<double>(a, b)(rng);
}
// A nonzero exponent in [-3, 3].
double exponent(std::mt19937& rng) {
  const double m = uniform(rng, 0.2, 3.0);
  return uniform(rng, 0.0, 1.0) < 0.5 ? -m : m;
}
std::string num(double v) { return fmt::format("{:.17g}", v); }
double at(const Params& p, const char* key) { return p.values.at(key); }

Params lambda_mu(std::mt19937& rng) {
  Params p;
  p.values["lambda"] = uniform(rng, 0.1, 20.0);
  p.values["mu"] = uniform(rng, 0.1, 10.0);
  return p;
}

Lame lambda_mu_column(const Params& p) { return {at(p, "lambda"), at(p, "mu")}; }

struct Family {
  std::string name;
  TableLame table;
  Randomizer random;
  bool optional = false;  // registered by another part of the library, may be absent
  friend void PrintTo(const Family& f, std::ostream* os) { *os << f.name; }
};

std::vector<Family> families() {
  std::vector<Family> f;
  f.push_back({"linear_corotational", lambda_mu_column, lambda_mu});
  f.push_back({"stvk", lambda_mu_column, lambda_mu, true});
  f.push_back({"hencky", lambda_mu_column, lambda_mu});
  auto with_m = [](std::mt19937& rng) {
    Params p = lambda_mu(rng);
    p.values["m"] = exponent(rng);
    return p;
  };
  f.push_back({"seth_hill", lambda_mu_column, with_m});
  f.push_back({"symmetric_seth_hill", lambda_mu_column, with_m});
  // Hill: any f with f(1) = 0, f'(1) = 1, e.g. the Seth-Hill strain (x^a - 1)/a.
  f.push_back({"hill", lambda_mu_column, [](std::mt19937& rng) {
                 Params p = lambda_mu(rng);
                 const double a = exponent(rng);
                 p.functions["f"] = fmt::format("(x^{} - 1)/{}", num(a), num(a));
                 return p;
               }});
  f.push_back({"neo_hookean", lambda_mu_column, lambda_mu});
  f.push_back({"neo_hookean_ogden", lambda_mu_column, lambda_mu});
  f.push_back({"stable_neo_hookean_eq13",
               [](const Params& p) { return Lame{at(p, "lambda") - at(p, "mu"), at(p, "mu")}; },
               lambda_mu, true});
  f.push_back({"sts", lambda_mu_column, [](std::mt19937& rng) {
                 Params p = lambda_mu(rng);
                 p.values["mu4"] = uniform(rng, -5.0, 5.0);
                 return p;
               }});
  f.push_back({"valanis_landel", lambda_mu_column, lambda_mu});
  // New Valanis-Landel: (h''(1), f''(1)/2). Random f, h with h'(1) = 0 = f'(1):
  //   f = c1 (x-1)^2 + c2 (x-1)^3  -> f''(1) = 2 c1;  h = c3 log^2 x + c4 (x-1)^3 -> h''(1) = 2 c3.
  // Without "f"/"h" keys the defaults (functions of lambda, mu) are used.
  f.push_back({"valanis_landel_new",
               [](const Params& p) {
                 if (!p.values.count("c1")) return lambda_mu_column(p);  // default f, h
                 return Lame{2.0 * at(p, "c3"), at(p, "c1")};
               },
               [](std::mt19937& rng) {
                 Params p = lambda_mu(rng);
                 if (uniform(rng, 0.0, 1.0) < 0.3) return p;
                 const double c1 = uniform(rng, 0.1, 5.0), c2 = uniform(rng, -2.0, 2.0);
                 const double c3 = uniform(rng, 0.1, 10.0), c4 = uniform(rng, -2.0, 2.0);
                 p.functions["f"] = fmt::format("{}*(x-1)^2 + {}*(x-1)^3", num(c1), num(c2));
                 p.functions["h"] = fmt::format("{}*log(x)^2 + {}*(x-1)^3", num(c3), num(c4));
                 p.values["c1"] = c1;  // kept for the column formula, removed before make
                 p.values["c3"] = c3;
                 return p;
               }});
  // Xu: (g''(1) + h''(1), (f''(1) + g''(1))/2) with the g sum over i < j.
  //   f = a (x-1)^2, g = b (x-1)^2 + e (x-1)^3, h = c log^2 x.
  f.push_back({"valanis_landel_xu",
               [](const Params& p) {
                 if (!p.values.count("a")) return lambda_mu_column(p);  // default f, g, h
                 const double f2 = 2.0 * at(p, "a"), g2 = 2.0 * at(p, "b"), h2 = 2.0 * at(p, "c");
                 return Lame{g2 + h2, 0.5 * (f2 + g2)};
               },
               [](std::mt19937& rng) {
                 Params p = lambda_mu(rng);
                 if (uniform(rng, 0.0, 1.0) < 0.3) return p;
                 const double a = uniform(rng, 0.1, 5.0), b = uniform(rng, -1.0, 3.0);
                 const double e = uniform(rng, -2.0, 2.0), c = uniform(rng, 0.1, 10.0);
                 p.functions["f"] = fmt::format("{}*(x-1)^2", num(a));
                 p.functions["g"] = fmt::format("{}*(x-1)^2 + {}*(x-1)^3", num(b), num(e));
                 p.functions["h"] = fmt::format("{}*log(x)^2", num(c));
                 p.values["a"] = a;
                 p.values["b"] = b;
                 p.values["c"] = c;
                 return p;
               }});
  f.push_back({"peng_landel", [](const Params& p) { return Lame{0.0, at(p, "E") / 3.0}; },
               [](std::mt19937& rng) {
                 Params p;
                 p.values["E"] = uniform(rng, 0.1, 30.0);
                 return p;
               }});
  auto mu_only = [](std::mt19937& rng) {
    Params p;
    p.values["mu"] = uniform(rng, 0.1, 10.0);
    return p;
  };
  f.push_back({"arap", [](const Params& p) { return Lame{0.0, at(p, "mu")}; }, mu_only});
  f.push_back({"symmetric_arap", [](const Params& p) { return Lame{0.0, at(p, "mu")}; }, mu_only});
  f.push_back({"symmetric_dirichlet", [](const Params& p) { return Lame{0.0, 2.0 * at(p, "mu")}; },
               mu_only});
  f.push_back({"ogden",
               [](const Params& p) {
                 double mu = 0.0;
                 for (const char* k : {"1", "2", "3"}) {
                   mu += 0.5 * at(p, (std::string("mu") + k).c_str()) *
                         (at(p, (std::string("alpha") + k).c_str()) - 1.0);
                 }
                 return Lame{0.0, mu};
               },
               [](std::mt19937& rng) {
                 Params p;
                 for (const char* k : {"1", "2", "3"}) {
                   const bool active = uniform(rng, 0.0, 1.0) < 0.8;
                   p.values[std::string("mu") + k] = active ? uniform(rng, -2.0, 2.0) : 0.0;
                   p.values[std::string("alpha") + k] = 1.5 * exponent(rng);
                 }
                 return p;
               }});
  f.push_back({"mooney_rivlin",
               [](const Params& p) {
                 return Lame{-4.0 / 3.0 * (2.0 * at(p, "C1") + 5.0 * at(p, "C2")), at(p, "C1")};
               },
               [](std::mt19937& rng) {
                 Params p;
                 p.values["C1"] = uniform(rng, -3.0, 3.0);
                 p.values["C2"] = uniform(rng, -3.0, 3.0);
                 return p;
               }});
  return f;
}

bool registered(const std::string& name) {
  for (const auto& info : MaterialCatalog::instance().all()) {
    if (info.name == name) return true;
  }
  return false;
}

// The parameters the catalog knows (drops the helper values kept for the column formula).
Params for_catalog(const std::string& name, const Params& p) {
  const MaterialInfo& info = MaterialCatalog::instance().find(name);
  Params out;
  out.functions = p.functions;
  for (const auto& spec : info.parameters) {
    if (p.values.count(spec.key)) out.values[spec.key] = p.values.at(spec.key);
  }
  return out;
}

void expect_lame(const Lame& got, const Lame& want, const std::string& what) {
  const double scale = std::max({1.0, std::abs(want.lambda), std::abs(want.mu)});
  EXPECT_NEAR(got.lambda, want.lambda, 1e-10 * scale) << what << " (lambda_Lame)";
  EXPECT_NEAR(got.mu, want.mu, 1e-10 * scale) << what << " (mu_Lame)";
}

class Table1Lame : public ::testing::TestWithParam<Family> {
 protected:
  void SetUp() override {
    if (!registered(GetParam().name)) {
      if (GetParam().optional) GTEST_SKIP() << GetParam().name << " is not registered";
      FAIL() << GetParam().name << " is a Table 1 family and must be registered";
    }
  }
};

TEST_P(Table1Lame, DefaultsMatchTheTable) {
  const Family& fam = GetParam();
  const Params defaults = MaterialCatalog::instance().complete(fam.name, {});
  const auto material = MaterialCatalog::instance().make(fam.name);
  expect_lame(lame_from_energy(*material), fam.table(defaults), fam.name + " at the defaults");
}

TEST_P(Table1Lame, RandomParametersMatchTheTable) {
  const Family& fam = GetParam();
  std::mt19937 rng(2024);
  for (int trial = 0; trial < 8; ++trial) {
    Params given = fam.random(rng);
    const Params full = [&] {
      Params c = MaterialCatalog::instance().complete(fam.name, for_catalog(fam.name, given));
      for (const auto& [k, v] : given.values) c.values.emplace(k, v);  // helper values back
      return c;
    }();
    const auto material = MaterialCatalog::instance().make(fam.name, for_catalog(fam.name, given));
    std::string what = fam.name;
    for (const auto& [k, v] : full.values) what += fmt::format(" {}={}", k, v);
    for (const auto& [k, v] : full.functions) what += fmt::format(" {}='{}'", k, v);
    expect_lame(lame_from_energy(*material), fam.table(full), what);
  }
}

// d^2 psi / d s_i d s_j at (1, 1, 1) by central differences of psi_stretch (Richardson).
Mat3 fd_stretch_hessian(const Material& m) {
  auto psi = [&](const Vec3& s) { return m.psi_stretch(s); };
  Mat3 H;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) H(i, j) = mixed_difference(psi, Vec3(Vec3::Ones()), Vec3(Vec3::Unit(i)), Vec3(Vec3::Unit(j)), 1e-3);
  return H;
}

TEST_P(Table1Lame, RestHessianIsTheEnergys) {
  const Family& fam = GetParam();
  std::mt19937 rng(99);
  for (int trial = 0; trial < 4; ++trial) {
    const auto material = trial == 0 ? MaterialCatalog::instance().make(fam.name)
                                     : MaterialCatalog::instance().make(
                                           fam.name, for_catalog(fam.name, fam.random(rng)));
    const Mat3 H = material->hess_stretch(Vec3::Ones());
    const Mat3 fd = fd_stretch_hessian(*material);
    EXPECT_LE((H - fd).norm(), 1e-6 * std::max(1.0, fd.norm())) << fam.name << "\n" << H << "\n" << fd;
  }
}

INSTANTIATE_TEST_SUITE_P(Table1, Table1Lame, ::testing::ValuesIn(families()),
                         [](const auto& p) { return p.param.name; });

}  // namespace
}  // namespace sinew
