#include "sinew/motion/obstacle.hpp"

#include <algorithm>
#include <cmath>

#include "sinew/core/error.hpp"

namespace sinew {
namespace {

// Any unit vector perpendicular to a (for a point exactly on an axis).
Eigen::Vector3d perpendicular(const Eigen::Vector3d& a) {
  const Eigen::Vector3d trial = std::abs(a.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  return (trial - trial.dot(a) * a).normalized();
}

// Query of a point at offset r (|r| = rho) from the nearest point of a "core" (a point or a
// segment) of a rounded shape: distance rho - radius, normal r / rho, and
// dn/dp = (I - n n^T - P) / rho, where P projects on the directions along which the nearest core
// point slides with p (the segment axis for a capsule body, nothing for a sphere).
SurfaceQuery rounded(const Eigen::Vector3d& p, const Eigen::Vector3d& r, double radius, const Mat3& sliding,
                     const Eigen::Vector3d& fallback_normal) {
  SurfaceQuery q;
  const double rho = r.norm();
  q.distance = rho - radius;
  if (rho > 1e-300) {
    q.normal = r / rho;
    q.normal_derivative = (Mat3::Identity() - q.normal * q.normal.transpose() - sliding) / rho;
  } else {
    q.normal = fallback_normal;  // on the core itself: any direction is as near
  }
  q.closest = p - q.distance * q.normal;
  return q;
}

}  // namespace

PlaneObstacle::PlaneObstacle(const Eigen::Vector3d& point, const Eigen::Vector3d& normal)
    : point_(point), normal_(normal.normalized()) {
  if (!(normal.norm() > 0.0)) throw Error("plane normal must be non-zero", "plane");
}

SurfaceQuery PlaneObstacle::query(const Eigen::Vector3d& p) const {
  SurfaceQuery q;
  q.distance = normal_.dot(p - point_);
  q.normal = normal_;
  q.closest = p - q.distance * normal_;
  return q;
}

SphereObstacle::SphereObstacle(const Eigen::Vector3d& center, double radius) : center_(center), radius_(radius) {
  if (!(radius > 0.0)) throw Error("sphere radius must be positive", "sphere");
}

SurfaceQuery SphereObstacle::query(const Eigen::Vector3d& p) const {
  return rounded(p, p - center_, radius_, Mat3::Zero(), Eigen::Vector3d::UnitZ());
}

CapsuleObstacle::CapsuleObstacle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double radius)
    : a_(a), b_(b), radius_(radius) {
  if (!(radius > 0.0)) throw Error("capsule radius must be positive", "capsule");
  if (!((b - a).norm() > 0.0)) throw Error("capsule end points must differ", "capsule");
}

SurfaceQuery CapsuleObstacle::query(const Eigen::Vector3d& p) const {
  const Eigen::Vector3d axis = b_ - a_;
  const double t = (p - a_).dot(axis) / axis.squaredNorm();
  const Eigen::Vector3d e = axis.normalized();
  if (t <= 0.0) return rounded(p, p - a_, radius_, Mat3::Zero(), -e);
  if (t >= 1.0) return rounded(p, p - b_, radius_, Mat3::Zero(), e);
  // Along the body the nearest axis point slides with p along e.
  return rounded(p, p - (a_ + t * axis), radius_, e * e.transpose(), perpendicular(e));
}

CylinderObstacle::CylinderObstacle(const Eigen::Vector3d& center, const Eigen::Vector3d& axis, double radius,
                                   double length)
    : center_(center), axis_(axis.normalized()), radius_(radius), half_length_(0.5 * length) {
  if (!(axis.norm() > 0.0)) throw Error("cylinder axis must be non-zero", "cylinder");
  if (!(radius > 0.0) || !(length > 0.0)) throw Error("cylinder radius and length must be positive", "cylinder");
}

SurfaceQuery CylinderObstacle::query(const Eigen::Vector3d& p) const {
  const Eigen::Vector3d rel = p - center_;
  const double h = rel.dot(axis_);
  const Eigen::Vector3d r = rel - h * axis_;
  const double rho = r.norm();
  const Eigen::Vector3d radial = rho > 1e-300 ? Eigen::Vector3d(r / rho) : perpendicular(axis_);
  const double d_side = rho - radius_, d_cap = std::abs(h) - half_length_;
  SurfaceQuery q;
  if (d_side <= 0.0 && d_cap <= 0.0) {
    // Inside: the nearer of the side wall and the caps (the signed distance is their max).
    if (d_side >= d_cap) {
      q.distance = d_side;
      q.normal = radial;
      if (rho > 1e-300)
        q.normal_derivative = (Mat3::Identity() - axis_ * axis_.transpose() - radial * radial.transpose()) / rho;
    } else {
      q.distance = d_cap;
      q.normal = h >= 0.0 ? axis_ : Eigen::Vector3d(-axis_);
    }
    q.closest = p - q.distance * q.normal;
    return q;
  }
  // Outside: the nearest point of the solid (radial part clamped to the radius, height to the caps).
  const double h_near = std::clamp(h, -half_length_, half_length_);
  const Eigen::Vector3d near = center_ + h_near * axis_ + std::min(rho, radius_) * radial;
  const Eigen::Vector3d diff = p - near;
  q.distance = diff.norm();
  q.normal = diff / q.distance;
  q.closest = near;
  return q;
}

BoxObstacle::BoxObstacle(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi)
    : center_(0.5 * (lo + hi)), half_(0.5 * (hi - lo)) {
  if (!(half_.array() > 0.0).all()) throw Error("box max must exceed min in every coordinate", "box");
}

SurfaceQuery BoxObstacle::query(const Eigen::Vector3d& p) const {
  const Eigen::Vector3d rel = p - center_;
  const Eigen::Vector3d excess = rel.cwiseAbs() - half_;
  SurfaceQuery q;
  if ((excess.array() <= 0.0).all()) {
    // Inside: the nearest face (the signed distance is the largest excess); flat, so dn/dp = 0.
    int i = 0;
    q.distance = excess.maxCoeff(&i);
    q.normal = Eigen::Vector3d::Unit(i) * (rel(i) >= 0.0 ? 1.0 : -1.0);
    q.closest = p - q.distance * q.normal;
    return q;
  }
  const Eigen::Vector3d near = center_ + rel.cwiseMax(-half_).cwiseMin(half_);
  const Eigen::Vector3d diff = p - near;
  q.distance = diff.norm();
  q.normal = diff / q.distance;
  q.closest = near;
  return q;
}

Obstacle::Obstacle(std::string name, std::shared_ptr<const ObstacleShape> shape, RigidMotion path)
    : name_(std::move(name)), shape_(std::move(shape)), path_(std::move(path)) {
  validate_motion(path_, name_);
}

bool Obstacle::moves() const { return !std::holds_alternative<Pinned>(path_); }

SurfaceQuery Obstacle::query(const Eigen::Vector3d& p, double frame) const {
  const RigidTransform T = pose(frame);
  SurfaceQuery q = shape_->query(T.R.transpose() * (p - T.t));
  q.normal = T.R * q.normal;
  q.closest = T.apply(q.closest);
  q.normal_derivative = T.R * q.normal_derivative * T.R.transpose();
  return q;
}

Eigen::Vector3d Obstacle::displacement(const Eigen::Vector3d& p, double frame0, double frame1) const {
  const RigidTransform T0 = pose(frame0), T1 = pose(frame1);
  return T1.apply(T0.R.transpose() * (p - T0.t)) - p;
}

Eigen::Vector3d Obstacle::velocity(const Eigen::Vector3d& p, double frame, double seconds_per_frame) const {
  constexpr double kDelta = 1e-6;  // frames
  return displacement(p, frame, frame + kDelta) / (kDelta * seconds_per_frame);
}

}  // namespace sinew
