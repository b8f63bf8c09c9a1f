#include "sinew/mesh/shape_surfaces.hpp"

#include <cmath>
#include <numbers>
#include <vector>

#include "sinew/core/error.hpp"

namespace sinew {
namespace {

// Two unit vectors completing `axis` (unit) to a right-handed frame.
std::pair<Eigen::Vector3d, Eigen::Vector3d> perpendiculars(const Eigen::Vector3d& axis) {
  const Eigen::Vector3d helper = std::abs(axis.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d u = axis.cross(helper).normalized();
  return {u, axis.cross(u)};
}

// Surface of revolution about `axis` through `origin` of a profile (r, z) that starts and ends
// on the axis (r = 0 there: the poles), oriented outward.
TriangleSurface revolve(const std::vector<Eigen::Vector2d>& profile, const Eigen::Vector3d& origin,
                        const Eigen::Vector3d& axis_in, int segments) {
  if (segments < 3) throw Error("a surface of revolution needs at least 3 segments");
  const Eigen::Vector3d axis = axis_in.normalized();
  const auto [u, w] = perpendiculars(axis);
  const int rings = static_cast<int>(profile.size()) - 2;
  TriangleSurface s;
  s.vertices.resize(2 + rings * segments, 3);
  s.vertices.row(0) = (origin + profile.front().y() * axis).transpose();
  for (int i = 0; i < rings; ++i)
    for (int k = 0; k < segments; ++k) {
      const double phi = 2.0 * std::numbers::pi * k / segments;
      const Eigen::Vector2d& p = profile[static_cast<size_t>(i + 1)];
      s.vertices.row(1 + i * segments + k) = (origin + p.y() * axis + p.x() * (std::cos(phi) * u + std::sin(phi) * w)).transpose();
    }
  const int top = 1 + rings * segments;
  s.vertices.row(top) = (origin + profile.back().y() * axis).transpose();
  std::vector<Eigen::Vector3i> tris;
  auto ring = [&](int i, int k) { return 1 + i * segments + (k % segments); };
  for (int k = 0; k < segments; ++k) {
    tris.emplace_back(0, ring(0, k + 1), ring(0, k));
    for (int i = 0; i + 1 < rings; ++i) {
      tris.emplace_back(ring(i, k), ring(i, k + 1), ring(i + 1, k + 1));
      tris.emplace_back(ring(i, k), ring(i + 1, k + 1), ring(i + 1, k));
    }
    tris.emplace_back(top, ring(rings - 1, k), ring(rings - 1, k + 1));
  }
  s.faces.resize(static_cast<Eigen::Index>(tris.size()), 3);
  for (size_t t = 0; t < tris.size(); ++t) s.faces.row(static_cast<Eigen::Index>(t)) = tris[t].transpose();
  if (s.volume() < 0.0) s.faces.col(1).swap(s.faces.col(2));  // profile went the other way round
  return s;
}

}  // namespace

TriangleSurface capsule_surface(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double radius, int segments) {
  if (!(radius > 0.0)) throw Error("a capsule needs a positive radius");
  const double length = (b - a).norm();
  const Eigen::Vector3d axis = length > 0.0 ? Eigen::Vector3d((b - a) / length) : Eigen::Vector3d::UnitZ();
  const int quarter = std::max(2, segments / 4);
  std::vector<Eigen::Vector2d> profile;
  for (int i = 0; i <= quarter; ++i) {  // lower hemisphere, pole to equator
    const double t = std::numbers::pi / 2 * (1.0 - double(i) / quarter);
    profile.emplace_back(radius * std::cos(t), -radius * std::sin(t));
  }
  for (int i = 0; i <= quarter; ++i) {  // upper hemisphere, equator to pole
    const double t = std::numbers::pi / 2 * double(i) / quarter;
    profile.emplace_back(radius * std::cos(t), length + radius * std::sin(t));
  }
  if (length == 0.0) profile.erase(profile.begin() + quarter);  // one equator ring, not two
  profile.front().x() = profile.back().x() = 0.0;
  return revolve(profile, a, axis, segments);
}

TriangleSurface sphere_surface(const Eigen::Vector3d& center, double radius, int segments) {
  return capsule_surface(center, center, radius, segments);
}

TriangleSurface cylinder_surface(const Eigen::Vector3d& center, const Eigen::Vector3d& axis, double radius, double length,
                                 int segments) {
  if (!(radius > 0.0) || !(length > 0.0) || !(axis.norm() > 0.0))
    throw Error("a cylinder needs a positive radius and length and a non-zero axis");
  const double h = 0.5 * length;
  return revolve({{0.0, -h}, {radius, -h}, {radius, h}, {0.0, h}}, center, axis, segments);
}

TriangleSurface box_surface(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  if (!(lo.array() < hi.array()).all()) throw Error("a box needs lo < hi in every coordinate");
  TriangleSurface s;
  s.vertices.resize(8, 3);
  for (int c = 0; c < 8; ++c)
    s.vertices.row(c) << (c & 1 ? hi.x() : lo.x()), (c & 2 ? hi.y() : lo.y()), (c & 4 ? hi.z() : lo.z());
  s.faces.resize(12, 3);
  // Two outward triangles per side (corner bits: 1 = +x, 2 = +y, 4 = +z).
  s.faces << 0, 2, 3, 0, 3, 1,   // -z
             4, 5, 7, 4, 7, 6,   // +z
             0, 1, 5, 0, 5, 4,   // -y
             2, 6, 7, 2, 7, 3,   // +y
             0, 4, 6, 0, 6, 2,   // -x
             1, 3, 7, 1, 7, 5;   // +x
  return s;
}

TriangleSurface square_surface(const Eigen::Vector3d& point, const Eigen::Vector3d& normal, double half_size) {
  if (!(half_size > 0.0) || !(normal.norm() > 0.0)) throw Error("a square needs a positive size and a non-zero normal");
  const auto [u, w] = perpendiculars(normal.normalized());
  TriangleSurface s;
  s.vertices.resize(4, 3);
  s.vertices.row(0) = (point - half_size * u - half_size * w).transpose();
  s.vertices.row(1) = (point + half_size * u - half_size * w).transpose();
  s.vertices.row(2) = (point + half_size * u + half_size * w).transpose();
  s.vertices.row(3) = (point - half_size * u + half_size * w).transpose();
  s.faces.resize(2, 3);
  s.faces << 0, 1, 2, 0, 2, 3;  // u x w = normal: counter-clockwise seen from the normal side
  return s;
}

}  // namespace sinew
