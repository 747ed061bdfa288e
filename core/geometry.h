#pragma once
// Shared vector types and angle helpers. Transforms are named xFromY: p_x = xFromY * p_y.
#include <Eigen/Geometry>
#include <numbers>

namespace omnicam {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Vec3f = Eigen::Vector3f;
using Rigid = Eigen::Isometry3d;

constexpr double kPi = std::numbers::pi;
constexpr double radians(double degrees) { return degrees * kPi / 180.0; }
constexpr double degrees(double radians_) { return radians_ * 180.0 / kPi; }

}  // namespace omnicam
