#include "sinew/mesh/shape_mesh.hpp"

#include <cmath>
#include <fmt/format.h>
#include <numbers>
#include <utility>
#include <vector>

#include "sinew/core/error.hpp"

namespace sinew {
namespace {

// Two unit vectors completing the unit `axis` to a right-handed frame.
std::pair<Eigen::Vector3d, Eigen::Vector3d> perpendiculars(const Eigen::Vector3d& axis) {
  const Eigen::Vector3d helper = std::abs(axis.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d u = axis.cross(helper).normalized();
  return {u, axis.cross(u)};
}

// A solid of revolution: profile points (axial position, radius) from the bottom pole to the
// top pole (radius 0 at both ends), swept around `axis` through `origin`.
TriangleSurface revolve(const Eigen::Vector3d& origin, const Eigen::Vector3d& axis,
                        const std::vector<std::pair<double, double>>& profile, int segments) {
  if (segments < 3) throw Error(fmt::format("needs at least 3 segments, got {}", segments), "shape mesh");
  const Eigen::Vector3d w = axis.normalized();
  const auto [u, v] = perpendiculars(w);
  std::vector<Eigen::Vector3d> points;
  std::vector<std::vector<int>> rings;  // vertex numbers of each profile point (one for a pole)
  for (const auto& [z, r] : profile) {
    std::vector<int> ring;
    const int n = r > 0.0 ? segments : 1;
    for (int k = 0; k < n; ++k) {
      const double phi = 2.0 * std::numbers::pi * k / segments;
      ring.push_back(static_cast<int>(points.size()));
      points.push_back(origin + z * w + r * (std::cos(phi) * u + std::sin(phi) * v));
    }
    rings.push_back(std::move(ring));
  }
  std::vector<Eigen::Vector3i> faces;
  for (std::size_t i = 0; i + 1 < rings.size(); ++i) {
    const auto &lo = rings[i], &hi = rings[i + 1];
    for (int k = 0; k < segments; ++k) {
      const int k1 = (k + 1) % segments;
      // Seen from outside, u -> v is counter-clockwise about +w, so (lo k, lo k1, hi k1) faces out.
      if (lo.size() == 1) {
        faces.emplace_back(lo[0], hi[k1], hi[k]);
      } else if (hi.size() == 1) {
        faces.emplace_back(lo[k], lo[k1], hi[0]);
      } else {
        faces.emplace_back(lo[k], lo[k1], hi[k1]);
        faces.emplace_back(lo[k], hi[k1], hi[k]);
      }
    }
  }
  TriangleSurface s;
  s.vertices.resize(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t i = 0; i < points.size(); ++i) s.vertices.row(static_cast<Eigen::Index>(i)) = points[i].transpose();
  s.faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t i = 0; i < faces.size(); ++i) s.faces.row(static_cast<Eigen::Index>(i)) = faces[i].transpose();
  return s;
}

// Latitudes of a hemisphere of `radius` whose flat side is at axial 0: from the pole (at
// -radius when `bottom`) to the equator, excluding the equator.
void add_hemisphere(std::vector<std::pair<double, double>>& profile, double offset, double radius, int rings, bool bottom) {
  for (int i = 0; i < rings; ++i) {
    const double theta = 0.5 * std::numbers::pi * (bottom ? i : rings - i) / rings;  // from the pole
    const double z = radius * std::cos(theta), r = radius * std::sin(theta);
    profile.emplace_back(offset + (bottom ? -z : z), r);
  }
}

}  // namespace

TriangleSurface sphere_mesh(const Eigen::Vector3d& center, double radius, int segments) {
  return capsule_mesh(center, center, radius, segments);
}

TriangleSurface capsule_mesh(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double radius, int segments) {
  if (!(radius > 0.0)) throw Error(fmt::format("radius must be positive, got {}", radius), "shape mesh");
  const double length = (b - a).norm();
  const Eigen::Vector3d axis = length > 0.0 ? Eigen::Vector3d((b - a) / length) : Eigen::Vector3d::UnitZ();
  const int rings = std::max(2, segments / 4);
  std::vector<std::pair<double, double>> profile;
  add_hemisphere(profile, 0.0, radius, rings, true);
  profile.emplace_back(0.0, radius);
  if (length > 0.0) profile.emplace_back(length, radius);
  std::vector<std::pair<double, double>> top;
  add_hemisphere(top, length, radius, rings, false);
  profile.insert(profile.end(), top.begin() + 1, top.end());  // skip the equator (already there)
  profile.emplace_back(length + radius, 0.0);
  return revolve(a, axis, profile, segments);
}

TriangleSurface cylinder_mesh(const Eigen::Vector3d& center, const Eigen::Vector3d& axis, double radius, double length,
                              int segments) {
  if (!(radius > 0.0) || !(length > 0.0)) throw Error("cylinder radius and length must be positive", "shape mesh");
  const Eigen::Vector3d w = axis.normalized();
  const double h = 0.5 * length;
  return revolve(center, w, {{-h, 0.0}, {-h, radius}, {h, radius}, {h, 0.0}}, segments);
}

TriangleSurface box_mesh(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  if (!(hi.array() > lo.array()).all()) throw Error("box needs hi > lo in every coordinate", "shape mesh");
  TriangleSurface s;
  s.vertices.resize(8, 3);
  for (int i = 0; i < 8; ++i)
    s.vertices.row(i) << (i & 1 ? hi.x() : lo.x()), (i & 2 ? hi.y() : lo.y()), (i & 4 ? hi.z() : lo.z());
  // Two outward triangles per side (vertex bit 1: x, 2: y, 4: z).
  s.faces.resize(12, 3);
  s.faces << 0, 2, 3, 0, 3, 1,  // z = lo
      4, 5, 7, 4, 7, 6,         // z = hi
      0, 1, 5, 0, 5, 4,         // y = lo
      2, 6, 7, 2, 7, 3,         // y = hi
      0, 4, 6, 0, 6, 2,         // x = lo
      1, 3, 7, 1, 7, 5;         // x = hi
  return s;
}

TriangleSurface square_mesh(const Eigen::Vector3d& center, const Eigen::Vector3d& normal, double half_size) {
  if (!(half_size > 0.0) || !(normal.norm() > 0.0)) throw Error("square needs a positive size and a normal", "shape mesh");
  const auto [u, v] = perpendiculars(normal.normalized());
  TriangleSurface s;
  s.vertices.resize(4, 3);
  s.vertices.row(0) = (center - half_size * u - half_size * v).transpose();
  s.vertices.row(1) = (center + half_size * u - half_size * v).transpose();
  s.vertices.row(2) = (center + half_size * u + half_size * v).transpose();
  s.vertices.row(3) = (center - half_size * u + half_size * v).transpose();
  s.faces.resize(2, 3);
  s.faces << 0, 1, 2, 0, 2, 3;  // u x v = normal: counter-clockwise seen from the normal side
  return s;
}

}  // namespace sinew
