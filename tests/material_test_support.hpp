#pragma once
// Shared oracles for material tests: random deformation gradients of every kind the
// acceptance criteria name and a numeric 9x9 eigendecomposition (used only here, never in the
// library). Finite differences come from the library's checker (material/derivative_check.hpp).
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <random>
#include <string>
#include <vector>

#include "sinew/core/types.hpp"
#include "sinew/material/derivative_check.hpp"
#include "sinew/material/material.hpp"

namespace sinew::test {

enum class FKind { Rotation, Moderate, LargeStretch, NearDegenerate, NearEqual, Inverted };

inline const char* to_string(FKind k) {
  switch (k) {
    case FKind::Rotation: return "rotation";
    case FKind::Moderate: return "moderate";
    case FKind::LargeStretch: return "large-stretch";
    case FKind::NearDegenerate: return "near-degenerate";
    case FKind::NearEqual: return "near-equal";
    case FKind::Inverted: return "inverted";
  }
  return "?";
}

struct SampleF {
  Mat3 F;
  FKind kind;
  Vec3 sigma;
};

inline Mat3 random_rotation(std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::Quaterniond q(n(rng), n(rng), n(rng), n(rng));
  q.normalize();
  return q.toRotationMatrix();
}

inline SampleF random_F(std::mt19937& rng, FKind kind) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  auto in = [&](double a, double b) { return a + (b - a) * u(rng); };
  Vec3 s;
  switch (kind) {
    case FKind::Rotation: s = Vec3::Ones(); break;
    case FKind::Moderate: s = Vec3(in(0.5, 1.6), in(0.5, 1.6), in(0.5, 1.6)); break;
    case FKind::LargeStretch: s = Vec3(in(2.5, 5.0), in(0.3, 5.0), in(0.4, 2.0)); break;
    case FKind::NearDegenerate: s = Vec3(in(0.5, 2.0), in(0.5, 2.0), in(0.01, 0.05)); break;
    case FKind::NearEqual: {
      const double a = in(0.5, 2.0);
      s = Vec3(a, a * (1.0 + 1e-9 * in(-1.0, 1.0)), in(0.5, 2.0));
      break;
    }
    case FKind::Inverted: s = Vec3(in(0.4, 2.0), in(0.4, 2.0), -in(0.1, 1.5)); break;
  }
  const Mat3 F = random_rotation(rng) * s.asDiagonal() * random_rotation(rng).transpose();
  return {F, kind, s};
}

// At least `per_kind` samples of each kind; inverted ones only where the energy is defined.
inline std::vector<SampleF> sample_set(unsigned seed, int per_kind, bool allow_inverted) {
  std::mt19937 rng(seed);
  std::vector<SampleF> out;
  for (FKind k : {FKind::Rotation, FKind::Moderate, FKind::LargeStretch, FKind::NearDegenerate,
                  FKind::NearEqual, FKind::Inverted}) {
    if (k == FKind::Inverted && !allow_inverted) continue;
    for (int i = 0; i < per_kind; ++i) out.push_back(random_F(rng, k));
  }
  return out;
}

// ||A - B|| / max(||B||, floor): relative, but absolute near zero (moduli are O(1) in the
// tests, so a quantity below 1e-4 counts as zero and is compared absolutely).
template <class A, class B>
double rel_error(const A& a, const B& b, double floor = 1e-4) {
  return (a - b).norm() / std::max(b.norm(), floor);
}

inline Vec9 numeric_eigenvalues(const Mat9& H) {
  Eigen::SelfAdjointEigenSolver<Mat9> es(0.5 * (H + H.transpose()));
  return es.eigenvalues();
}

inline Mat9 numeric_projection(const Mat9& H, double floor) {
  Eigen::SelfAdjointEigenSolver<Mat9> es(0.5 * (H + H.transpose()));
  Vec9 v = es.eigenvalues();
  for (int k = 0; k < 9; ++k) v(k) = std::max(v(k), floor);
  return es.eigenvectors() * v.asDiagonal() * es.eigenvectors().transpose();
}

inline std::string describe(const SampleF& s) {
  return std::string(to_string(s.kind)) + " sigma=(" + std::to_string(s.sigma(0)) + ", " +
         std::to_string(s.sigma(1)) + ", " + std::to_string(s.sigma(2)) + ")";
}

}  // namespace sinew::test
