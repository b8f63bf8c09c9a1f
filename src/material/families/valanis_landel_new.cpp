#include "sinew/material/families/valanis_landel_new.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "sinew/core/error.hpp"

namespace sinew {

namespace {
Vec3 at_one(const ScalarFunction& fn, const char* key) {
  try {
    return fn.derivatives(1.0);
  } catch (const Error& e) {
    throw e.within(fmt::format("function '{}'", key));
  }
}
}  // namespace

ValanisLandelNew::ValanisLandelNew(ScalarFunction f, ScalarFunction h)
    : f_(std::move(f)), h_(std::move(h)) {
  // Rest stability: p_i(1, 1, 1) = f'(1) + h'(1) must vanish (relative to the stiffness).
  const Vec3 f1 = at_one(f_, "f"), h1 = at_one(h_, "h");
  const double scale = std::max({1.0, std::abs(f1(1)), std::abs(h1(1)), std::abs(f1(2)),
                                 std::abs(h1(2))});
  if (std::abs(f1(1) + h1(1)) > 1e-10 * scale) {
    throw Error(fmt::format("the rest shape must be stress-free: f'(1) + h'(1) = 0 is required, "
                            "got f'(1) = {}, h'(1) = {} for f(x) = {}, h(x) = {}",
                            f1(1), h1(1), f_.text(), h_.text()),
                "functions 'f', 'h'");
  }
}

Vec3 ValanisLandelNew::single(double s) const { return f_.derivatives(s); }
Vec3 ValanisLandelNew::volume(double J) const { return h_.derivatives(J); }

}  // namespace sinew
