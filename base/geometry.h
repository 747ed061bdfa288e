#pragma once
// Shared vector types and angle helpers. Transforms are named xFromY: p_x = xFromY * p_y.
#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <utility>

namespace omnicam {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Vec3f = Eigen::Vector3f;
using Rigid = Eigen::Isometry3d;

constexpr double kPi = std::numbers::pi;
constexpr double radians(double degrees) { return degrees * kPi / 180.0; }
constexpr double degrees(double radians_) { return radians_ * 180.0 / kPi; }

// An angle in radians wrapped to (−π, π].
inline double wrapAngle(double radians_) {
  const double wrapped = std::remainder(radians_, 2.0 * kPi);  // [−π, π]
  return wrapped <= -kPi ? wrapped + 2.0 * kPi : wrapped;
}

// Range (horizontal, metres) and bearing (radians counter-clockwise from the heading `yaw`, in
// (−π, π]) of the point `to` seen from `from`, both on the floor plan: what the thesis' EKF
// measures of a landmark, and what every ground truth of a sighting states.
inline Vec2 rangeBearingOnFloor(const Vec2& from, double yaw, const Vec2& to) {
  const double dx = to.x() - from.x(), dy = to.y() - from.y();
  return {std::hypot(dx, dy), wrapAngle(std::atan2(dy, dx) - yaw)};
}

// An orthonormal frame (e1, e2) perpendicular to `axis`; e1 is the projection of +X when
// possible (so a vertical cylinder's u = 0 faces +X), else of +Y. Shared by every engine's
// texture coordinates on cylinders and discs.
inline std::pair<Vec3, Vec3> perpendicularFrame(const Vec3& axis) {
  const Vec3 a = axis.normalized();
  Vec3 e1 = Vec3::UnitX() - a.x() * a;
  if (e1.norm() < 1e-6) e1 = Vec3::UnitY() - a.y() * a;
  e1.normalize();
  return {e1, a.cross(e1)};
}

}  // namespace omnicam
