#include "sinew/material/lame.hpp"

#include <cmath>
#include <fmt/format.h>

#include "sinew/core/error.hpp"

namespace sinew {

Lame lame_from_energy(const Material& material) {
  const Mat3 h = material.hess_stretch(Vec3::Ones());
  // Average the symmetric entries: exact symmetry holds analytically, this only
  // removes rounding differences between the (i, j) positions.
  const double d11 = h.diagonal().mean();
  const double d12 = (h(0, 1) + h(0, 2) + h(1, 2)) / 3.0;
  return {d12, 0.5 * (d11 - d12)};
}

YoungPoisson young_poisson(const Lame& l) {
  const double sum = l.lambda + l.mu;
  if (sum == 0.0) throw Error("lambda + mu = 0: Young's modulus and Poisson's ratio undefined", "Lame");
  return {l.mu * (3.0 * l.lambda + 2.0 * l.mu) / sum, l.lambda / (2.0 * sum)};
}

Lame lame_from_young_poisson(const YoungPoisson& ev) {
  if (!std::isfinite(ev.E) || !(ev.E > 0.0)) {
    throw Error(fmt::format("must be a positive finite number, got {}", ev.E), "E");
  }
  if (!std::isfinite(ev.nu) || !(ev.nu > -1.0) || !(ev.nu < 0.5)) {
    throw Error(fmt::format("must satisfy -1 < nu < 0.5, got {}", ev.nu), "nu");
  }
  return {ev.E * ev.nu / ((1.0 + ev.nu) * (1.0 - 2.0 * ev.nu)), ev.E / (2.0 * (1.0 + ev.nu))};
}

}  // namespace sinew
