#include "sinew/motion/amplitude.hpp"

#include <cmath>
#include <fmt/format.h>

#include "sinew/core/error.hpp"

namespace sinew {

double Amplitude::at(double frame) const {
  if (points.empty()) return 1.0;
  if (frame <= points.front().first) return points.front().second;
  if (frame >= points.back().first) return points.back().second;
  size_t i = 1;
  while (points[i].first < frame) ++i;
  const auto& [f0, a0] = points[i - 1];
  const auto& [f1, a1] = points[i];
  const double s = (frame - f0) / (f1 - f0);
  return (1.0 - s) * a0 + s * a1;
}

void validate_amplitude(const Amplitude& amplitude, const std::string& context) {
  const auto& p = amplitude.points;
  for (size_t i = 0; i < p.size(); ++i) {
    if (!std::isfinite(p[i].first) || !std::isfinite(p[i].second))
      throw Error(fmt::format("point {} has a non-finite value", i), context);
    if (i > 0 && !(p[i].first > p[i - 1].first))
      throw Error(fmt::format("point {} is not after point {} (frames must increase: {:g} <= {:g})", i, i - 1,
                              p[i].first, p[i - 1].first),
                  context);
  }
}

}  // namespace sinew
