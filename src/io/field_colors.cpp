#include "sinew/io/field_colors.hpp"

#include <algorithm>
#include <cmath>

namespace sinew {
namespace {

float srgb_to_linear(float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); }

}  // namespace

const std::vector<Eigen::Vector3f>& field_color_stops() {
  static const std::vector<Eigen::Vector3f> stops = [] {
    // Chosen in sRGB (what a colour picker shows), stored linear.
    const float srgb[][3] = {{0.15f, 0.10f, 0.40f}, {0.15f, 0.35f, 0.65f}, {0.10f, 0.60f, 0.55f},
                             {0.55f, 0.80f, 0.25f}, {0.99f, 0.90f, 0.15f}};
    std::vector<Eigen::Vector3f> s;
    for (const auto& c : srgb) s.emplace_back(srgb_to_linear(c[0]), srgb_to_linear(c[1]), srgb_to_linear(c[2]));
    return s;
  }();
  return stops;
}

Eigen::MatrixX3f field_colors(const Eigen::VectorXf& values, float lo, float hi) {
  const auto& stops = field_color_stops();
  const float segments = static_cast<float>(stops.size() - 1);
  Eigen::MatrixX3f colors(values.size(), 3);
  for (Eigen::Index i = 0; i < values.size(); ++i) {
    const float t = hi > lo ? std::clamp((values(i) - lo) / (hi - lo), 0.0f, 1.0f) : 0.5f;
    const float s = t * segments;
    const auto k = std::min(static_cast<std::size_t>(s), stops.size() - 2);
    const float a = s - static_cast<float>(k);
    colors.row(i) = ((1.0f - a) * stops[k] + a * stops[k + 1]).transpose();
  }
  return colors;
}

}  // namespace sinew
