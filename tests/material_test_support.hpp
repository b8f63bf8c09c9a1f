#pragma once
// Shared oracles for material tests: random deformation gradients of every kind the
// acceptance criteria name, Richardson-extrapolated central differences, and a numeric
// 9x9 eigendecomposition (used only here, never in the library).
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <random>
#include <string>
#include <vector>

#include "sinew/core/types.hpp"
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

// Central difference with one Richardson step: error O(h^4).
template <class Fn>
auto richardson(Fn&& diff, double h) {
  auto d1 = diff(h);
  auto d2 = diff(0.5 * h);
  return ((4.0 * d2 - d1) / 3.0).eval();
}

// The step stays well inside the smooth region around F: below the smallest singular value
// and, for inverted F, below the distance to the set sigma_i = -sigma_j where the polar
// rotation R = U V^T (and every energy built on it) has a Hessian singularity.
inline double fd_step(const Mat3& F) {
  const Vec3 s = signed_svd(F).sigma;
  double reach = std::min(1.0, s.cwiseAbs().minCoeff());
  for (int i = 0; i < 3; ++i)
    for (int j = i + 1; j < 3; ++j) reach = std::min(reach, std::abs(s(i) + s(j)));
  return 1e-3 * reach;
}

inline Mat3 fd_pk1(const Material& m, const Mat3& F) {
  const double h = fd_step(F);
  Mat3 P;
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) {
      auto diff = [&](double hh) {
        Mat3 Fp = F, Fm = F;
        Fp(r, c) += hh;
        Fm(r, c) -= hh;
        return Eigen::Matrix<double, 1, 1>((m.psi(Fp) - m.psi(Fm)) / (2.0 * hh));
      };
      P(r, c) = richardson(diff, h)(0);
    }
  return P;
}

inline Mat9 fd_hessian(const Material& m, const Mat3& F) {
  const double h = fd_step(F);
  Mat9 H;
  for (int col = 0; col < 9; ++col) {
    auto diff = [&](double hh) {
      Mat3 Fp = F, Fm = F;
      Fp(col % 3, col / 3) += hh;
      Fm(col % 3, col / 3) -= hh;
      return Vec9((vec(m.pk1(Fp)) - vec(m.pk1(Fm))) / (2.0 * hh));
    };
    H.col(col) = richardson(diff, h);
  }
  return H;
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
