#pragma once
#include "sinew/material/material.hpp"

namespace sinew {

// Mooney-Rivlin as written in paper 002 Table 1 (the literal reading, whose Lame parameters
// are the table's column; the standard isochoric form C1 (J^-2/3 I_1 - 3) + C2 (J^-4/3 I_2 - 3)
// has lambda_Lame = -4/3 (C1 + C2), mu_Lame = 2 (C1 + C2) instead; see docs):
//   Psi = C1 J^(-2/3) (I_1 - 3) + C2 J^(-4/3) (I_2 - 3),
//   I_1 = sum_i s_i^2, I_2 = s_0^2 s_1^2 + s_1^2 s_2^2 + s_2^2 s_0^2.
// lambda_Lame = -4/3 (2 C1 + 5 C2), mu_Lame = C1. P(I) = (2 C1 + 4 C2) I: stress-free at rest
// only when C2 = -C1/2. J > 0 only.
class MooneyRivlin final : public StretchMaterial {
 public:
  MooneyRivlin(double C1, double C2) : C1_(C1), C2_(C2) {}
  std::string name() const override { return "mooney_rivlin"; }
  Domain domain() const override { return Domain::PositiveJ; }

  double psi_stretch(const Vec3& s) const override;
  Vec3 grad_stretch(const Vec3& s) const override;
  Mat3 hess_stretch(const Vec3& s) const override;
  // Closed form (see the .cpp), exact for every s with J > 0.
  void pair_eigenvalues(const Vec3& s, const Vec3& p, const Mat3& h, Vec3& twist,
                        Vec3& flip) const override;

 private:
  double C1_, C2_;
};

}  // namespace sinew
