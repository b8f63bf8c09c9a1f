#pragma once
// Stress-stretch curves of one homogeneous deformation, the standard way to compare the
// large-deformation behaviour of materials normalised to the same (E, nu) (paper 002 Fig. 3):
//   uniaxial  F = diag(s, t, t), t solved so that the lateral stress P11 = P22 vanishes;
//   biaxial   F = diag(s, s, t), t solved so that P22 vanishes;
//   shear     F = I + s e0 e1^T (simple shear, no lateral solve).
// The nominal stress is the first Piola-Kirchhoff component P00 (P01 for shear).
#include <string>
#include <vector>

#include "sinew/material/material.hpp"

namespace sinew {

enum class CurveMode { Uniaxial, Biaxial, Shear };
CurveMode parse_curve_mode(const std::string& text);  // "uniaxial" | "biaxial" | "shear"
const char* to_string(CurveMode mode);

struct CurvePoint {
  double stretch = 1.0;  // s
  double lateral = 1.0;  // t (1 for shear)
  double J = 1.0;
  double stress = 0.0;  // P00, or P01 for shear
  double psi = 0.0;
};

// The deformation gradient of a mode at stretch s and lateral stretch t.
Mat3 curve_deformation(CurveMode mode, double stretch, double lateral);

// The lateral stretch t > 0 at which the lateral stress vanishes (uniaxial, biaxial),
// by bracketing from `guess` and safeguarded Newton (bisection when Newton leaves the
// bracket). Throws sinew::Error when no t in (1e-8, 1e8) brackets a root.
double solve_lateral_stretch(const Material& material, CurveMode mode, double stretch,
                             double guess = 1.0);

// steps + 1 equally spaced stretches from `from` to `to`. Requires finite from < to,
// steps >= 1, and from > 0 for uniaxial and biaxial modes (principal stretches).
std::vector<CurvePoint> stress_stretch_curve(const Material& material, CurveMode mode, double from,
                                             double to, int steps);

}  // namespace sinew
