#include "sinew/material/curve.hpp"

#include <cmath>
#include <fmt/format.h>
#include <limits>

#include "sinew/core/error.hpp"

namespace sinew {

CurveMode parse_curve_mode(const std::string& text) {
  if (text == "uniaxial") return CurveMode::Uniaxial;
  if (text == "biaxial") return CurveMode::Biaxial;
  if (text == "shear") return CurveMode::Shear;
  throw Error(fmt::format("unknown mode '{}' (expected uniaxial, biaxial or shear)", text), "mode");
}

const char* to_string(CurveMode mode) {
  switch (mode) {
    case CurveMode::Uniaxial: return "uniaxial";
    case CurveMode::Biaxial: return "biaxial";
    case CurveMode::Shear: return "shear";
  }
  return "?";
}

Mat3 curve_deformation(CurveMode mode, double stretch, double lateral) {
  switch (mode) {
    case CurveMode::Uniaxial: return Vec3(stretch, lateral, lateral).asDiagonal();
    case CurveMode::Biaxial: return Vec3(stretch, stretch, lateral).asDiagonal();
    case CurveMode::Shear: {
      Mat3 F = Mat3::Identity();
      F(0, 1) = stretch;
      return F;
    }
  }
  return Mat3::Identity();
}

namespace {

constexpr double kMinLateral = 1e-8, kMaxLateral = 1e8;

// The lateral stress as a function of t and its derivative dP/dt from the true Hessian
// (column-wise vec: entry (r, c) sits at 3c + r).
struct Lateral {
  double stress;
  double slope;
};

Lateral lateral_stress(const Material& m, CurveMode mode, double s, double t) {
  const Evaluation e = m.evaluate(curve_deformation(mode, s, t), Projection::None);
  if (mode == CurveMode::Uniaxial) {  // t moves F11 and F22; P11 = P22 by symmetry
    return {e.P(1, 1), e.hessian(4, 4) + e.hessian(4, 8)};
  }
  return {e.P(2, 2), e.hessian(8, 8)};  // biaxial: t is F22
}

}  // namespace

double solve_lateral_stretch(const Material& m, CurveMode mode, double s, double guess) {
  if (mode == CurveMode::Shear) return 1.0;
  const std::string where = fmt::format("{} stretch {:g}", to_string(mode), s);
  double t = std::isfinite(guess) && guess > 0.0 ? guess : 1.0;
  Lateral f = lateral_stress(m, mode, s, t);
  if (f.stress == 0.0) return t;

  // Bracket a sign change; the lateral stress grows with t for any sensible material.
  double lo = t, hi = t;
  if (f.stress > 0.0) {
    double flo = f.stress;
    while (flo > 0.0) {
      hi = lo;
      lo *= 0.5;
      if (lo < kMinLateral) {
        throw Error(fmt::format("no lateral stretch t > 0 makes the lateral stress vanish (it "
                                "stays positive down to t = {:g})",
                                kMinLateral),
                    where);
      }
      flo = lateral_stress(m, mode, s, lo).stress;
    }
  } else {
    double fhi = f.stress;
    while (fhi < 0.0) {
      lo = hi;
      hi *= 2.0;
      if (hi > kMaxLateral) {
        throw Error(fmt::format("no lateral stretch makes the lateral stress vanish (it stays "
                                "negative up to t = {:g})",
                                kMaxLateral),
                    where);
      }
      fhi = lateral_stress(m, mode, s, hi).stress;
    }
  }

  // Safeguarded Newton inside [lo, hi].
  t = 0.5 * (lo + hi);
  for (int iteration = 0; iteration < 200; ++iteration) {
    f = lateral_stress(m, mode, s, t);
    if (f.stress == 0.0) return t;
    (f.stress < 0.0 ? lo : hi) = t;
    double next = t - f.stress / f.slope;
    if (!(f.slope > 0.0) || !(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (std::abs(next - t) <= 4.0 * std::numeric_limits<double>::epsilon() * t) return next;
    t = next;
  }
  if (hi - lo <= 1e-10 * hi) return 0.5 * (lo + hi);
  throw Error("the lateral stretch did not converge", where);
}

std::vector<CurvePoint> stress_stretch_curve(const Material& m, CurveMode mode, double from,
                                             double to, int steps) {
  if (!std::isfinite(from)) throw Error("must be a finite number", "stretch-from");
  if (!std::isfinite(to)) throw Error("must be a finite number", "stretch-to");
  if (!(from < to)) {
    throw Error(fmt::format("must be smaller than stretch-to ({:g}), got {:g}", to, from),
                "stretch-from");
  }
  if (steps < 1) throw Error(fmt::format("must be at least 1, got {}", steps), "steps");
  if (mode != CurveMode::Shear && !(from > 0.0)) {
    throw Error(fmt::format("a principal stretch must be positive for {} mode, got {:g}",
                            to_string(mode), from),
                "stretch-from");
  }
  std::vector<CurvePoint> out;
  out.reserve(static_cast<std::size_t>(steps) + 1);
  double guess = 1.0;
  for (int k = 0; k <= steps; ++k) {
    CurvePoint p;
    p.stretch = k == steps ? to : from + (to - from) * k / steps;
    p.lateral = solve_lateral_stretch(m, mode, p.stretch, guess);
    guess = p.lateral;
    const Mat3 F = curve_deformation(mode, p.stretch, p.lateral);
    const Evaluation e = m.evaluate(F, Projection::None);
    p.J = F.determinant();
    p.stress = mode == CurveMode::Shear ? e.P(0, 1) : e.P(0, 0);
    p.psi = e.psi;
    out.push_back(p);
  }
  return out;
}

}  // namespace sinew
