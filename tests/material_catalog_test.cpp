// One shared derivative/eigensystem/projection test, run on every family in the catalog
// with its default parameters (paper 000 §4, paper 002 Eq. 1).
#include <gtest/gtest.h>

#include <cstdlib>

#include "material_test_support.hpp"
#include "sinew/core/error.hpp"
#include "sinew/material/catalog.hpp"

namespace sinew {
namespace {

using test::rel_error;

std::vector<std::string> all_names() {
  std::vector<std::string> names;
  for (const auto& f : MaterialCatalog::instance().all()) names.push_back(f.name);
  return names;
}

class EveryMaterial : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override { material = MaterialCatalog::instance().make(GetParam()); }
  std::vector<test::SampleF> samples() const {
    // SINEW_TEST_SEED explores other samples (e.g. a seed sweep before changing defaults).
    const char* seed = std::getenv("SINEW_TEST_SEED");
    return test::sample_set(seed ? static_cast<unsigned>(std::atoi(seed)) : 1234u, 10,
                            material->domain() == Domain::All);
  }
  std::unique_ptr<Material> material;
};

// The library's derivative checker (material/derivative_check.hpp) on every family: P against
// differences of psi, the true dP/dF against differences of P, at rotations, moderate, large,
// near-degenerate, near-equal and (where defined) inverted F.
TEST_P(EveryMaterial, Pk1MatchesFiniteDifferences) {
  const auto set = samples();
  ASSERT_GE(set.size(), 50u);
  for (const auto& s : set) {
    // Where P vanishes (rest, rotations) the checker compares against the stress of a 1e-4
    // strain instead: the finite difference itself is only that accurate.
    EXPECT_LE(check_material_derivatives(*material, s.F).pk1_error, 1e-6) << test::describe(s);
  }
}

TEST_P(EveryMaterial, HessianMatchesFiniteDifferences) {
  for (const auto& s : samples()) {
    EXPECT_LE(check_material_derivatives(*material, s.F).hessian_error, 1e-6) << test::describe(s);
  }
}

TEST_P(EveryMaterial, AnalyticEigensystemMatchesNumeric) {
  for (const auto& s : samples()) {
    const Mat9 H = material->hessian(s.F);
    const Eigensystem es = material->eigensystem(s.F);
    const double scale = std::max(1.0, H.norm());
    Vec9 analytic = es.values;
    std::sort(analytic.data(), analytic.data() + 9);
    EXPECT_LE((analytic - test::numeric_eigenvalues(H)).norm() / scale, 1e-8) << test::describe(s);
    EXPECT_LE((es.vectors.transpose() * es.vectors - Mat9::Identity()).norm(), 1e-10)
        << test::describe(s);
    for (int k = 0; k < 9; ++k) {
      EXPECT_LE((H * es.vectors.col(k) - es.values(k) * es.vectors.col(k)).norm() / scale, 1e-8)
          << test::describe(s) << " eigenpair " << k;
    }
  }
}

TEST_P(EveryMaterial, ProjectionsArePsdAndClampMatchesNumeric) {
  const double floor = material->projection_floor();
  for (const auto& s : samples()) {
    const Mat9 H = material->hessian(s.F);
    const double scale = std::max(1.0, H.norm());
    const Mat9 clamp = material->projected_hessian(s.F, Projection::Clamp);
    const Mat9 abs = material->projected_hessian(s.F, Projection::Abs);
    EXPECT_GE(test::numeric_eigenvalues(clamp).minCoeff(), std::min(floor, 0.0) - 1e-9 * scale)
        << test::describe(s);
    EXPECT_GE(test::numeric_eigenvalues(abs).minCoeff(), -1e-9 * scale) << test::describe(s);
    EXPECT_LE((clamp - test::numeric_projection(H, floor)).norm() / scale, 1e-8)
        << test::describe(s);
    EXPECT_LE((material->projected_hessian(s.F, Projection::None) - H).norm() / scale, 1e-12);
  }
}

TEST_P(EveryMaterial, EvaluateAgreesWithSeparateCalls) {
  for (const auto& s : samples()) {
    const Evaluation e = material->evaluate(s.F, Projection::Clamp);
    EXPECT_NEAR(e.psi, material->psi(s.F), 1e-10 * std::max(1.0, std::abs(e.psi)));
    EXPECT_LE(rel_error(e.P, material->pk1(s.F)), 1e-10);
    EXPECT_LE(rel_error(e.hessian, material->projected_hessian(s.F, Projection::Clamp)), 1e-9);
  }
}

TEST_P(EveryMaterial, RestStableMaterialsHaveZeroStressAtRest) {
  const auto& info = MaterialCatalog::instance().find(GetParam());
  if (!info.rest_stable) GTEST_SKIP() << "not rest-stable by design";
  EXPECT_LE(material->pk1(Mat3::Identity()).norm(), 1e-12);
  // Energies are shifted so the rest state stores nothing (energy limits and reports rely on it).
  EXPECT_NEAR(material->psi(Mat3::Identity()), 0.0, 1e-12);
  std::mt19937 rng(7);
  for (int i = 0; i < 5; ++i) {  // rest stability is rotation invariant
    const Mat3 R = test::random_rotation(rng);
    EXPECT_LE(material->pk1(R).norm(), 1e-10);
  }
}

TEST_P(EveryMaterial, DomainIsEnforced) {
  const Mat3 inverted = Vec3(1.0, 1.0, -0.5).asDiagonal();
  if (material->domain() == Domain::PositiveJ) {
    EXPECT_FALSE(material->in_domain(inverted));
    EXPECT_THROW(material->psi(inverted), Error);
    EXPECT_THROW(material->pk1(Mat3::Zero()), Error);
  } else {
    EXPECT_TRUE(std::isfinite(material->psi(inverted)));
  }
  Mat3 nan = Mat3::Identity();
  nan(1, 2) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(material->psi(nan), Error);
}

INSTANTIATE_TEST_SUITE_P(Catalog, EveryMaterial, ::testing::ValuesIn(all_names()),
                         [](const auto& p) { return p.param; });

}  // namespace
}  // namespace sinew
