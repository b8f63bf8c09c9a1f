#pragma once
// The shared derivative / eigensystem / projection battery of material_catalog_test.cpp as a
// function, so wrappers (nonlinearity exponent, mixes) built from any family get the same checks.
#include <gtest/gtest.h>

#include <limits>

#include "material_test_support.hpp"
#include "sinew/core/error.hpp"
#include "sinew/material/material.hpp"

namespace sinew::test {

struct BatteryOptions {
  unsigned seed = 1234u;
  int per_kind = 10;
  bool rest_stable = true;
};

inline void check_material_battery(const Material& m, const BatteryOptions& options = {}) {
  SCOPED_TRACE("material " + m.name());
  const auto set = sample_set(options.seed, options.per_kind, m.domain() == Domain::All);
  const double floor = m.projection_floor();
  for (const auto& s : set) {
    SCOPED_TRACE(describe(s));
    // P and the Hessian against Richardson central differences.
    EXPECT_LE(rel_error(m.pk1(s.F), difference_pk1(m, s.F)), 1e-6);
    const Mat9 H = m.hessian(s.F);
    EXPECT_LE(rel_error(H, difference_hessian(m, s.F)), 1e-6);

    // Analytic eigensystem against the numeric one.
    const Eigensystem es = m.eigensystem(s.F);
    const double scale = std::max(1.0, H.norm());
    Vec9 analytic = es.values;
    std::sort(analytic.data(), analytic.data() + 9);
    EXPECT_LE((analytic - numeric_eigenvalues(H)).norm() / scale, 1e-8);
    EXPECT_LE((es.vectors.transpose() * es.vectors - Mat9::Identity()).norm(), 1e-10);
    for (int k = 0; k < 9; ++k) {
      EXPECT_LE((H * es.vectors.col(k) - es.values(k) * es.vectors.col(k)).norm() / scale, 1e-8)
          << "eigenpair " << k;
    }

    // Projections.
    const Mat9 clamp = m.projected_hessian(s.F, Projection::Clamp);
    const Mat9 abs = m.projected_hessian(s.F, Projection::Abs);
    EXPECT_GE(numeric_eigenvalues(clamp).minCoeff(), std::min(floor, 0.0) - 1e-9 * scale);
    EXPECT_GE(numeric_eigenvalues(abs).minCoeff(), -1e-9 * scale);
    EXPECT_LE((clamp - numeric_projection(H, floor)).norm() / scale, 1e-8);
    EXPECT_LE((m.projected_hessian(s.F, Projection::None) - H).norm() / scale, 1e-12);

    // evaluate() against the separate calls.
    const Evaluation e = m.evaluate(s.F, Projection::Clamp);
    EXPECT_NEAR(e.psi, m.psi(s.F), 1e-10 * std::max(1.0, std::abs(e.psi)));
    EXPECT_LE(rel_error(e.P, m.pk1(s.F)), 1e-10);
    EXPECT_LE(rel_error(e.hessian, clamp), 1e-9);
  }

  if (options.rest_stable) {
    EXPECT_LE(m.pk1(Mat3::Identity()).norm(), 1e-12);
    std::mt19937 rng(7);
    for (int i = 0; i < 5; ++i) EXPECT_LE(m.pk1(random_rotation(rng)).norm(), 1e-10);
  }

  // Domain.
  const Mat3 inverted = Vec3(1.0, 1.0, -0.5).asDiagonal();
  if (m.domain() == Domain::PositiveJ) {
    EXPECT_FALSE(m.in_domain(inverted));
    EXPECT_THROW(m.psi(inverted), Error);
    EXPECT_THROW(m.pk1(Mat3::Zero()), Error);
  } else {
    EXPECT_TRUE(std::isfinite(m.psi(inverted)));
  }
  Mat3 nan = Mat3::Identity();
  nan(1, 2) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(m.psi(nan), Error);
}

}  // namespace sinew::test
