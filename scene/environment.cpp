#include "environment.h"

#include <algorithm>
#include <cmath>

namespace omnicam {

Eigen::Vector2d equirectFromDirection(const Vec3& direction) {
  const double elevation = std::atan2(direction.z(), std::hypot(direction.x(), direction.y()));
  return {0.5 - std::atan2(direction.y(), direction.x()) / (2.0 * kPi), 0.5 + elevation / kPi};
}

Vec3 directionFromEquirect(const Eigen::Vector2d& uv) {
  const double azimuth = kPi * (1.0 - 2.0 * uv.x()), elevation = kPi * (uv.y() - 0.5);
  const double horizontal = std::cos(elevation);
  return {horizontal * std::cos(azimuth), horizontal * std::sin(azimuth), std::sin(elevation)};
}

Vec3 Environment::worldFromImage(const Vec3& direction) const {
  if (rotationDeg == 0.0) return direction;
  const double c = std::cos(radians(rotationDeg)), s = std::sin(radians(rotationDeg));
  return {c * direction.x() - s * direction.y(), s * direction.x() + c * direction.y(), direction.z()};
}

Vec3 Environment::imageFromWorld(const Vec3& direction) const {
  if (rotationDeg == 0.0) return direction;
  const double c = std::cos(radians(rotationDeg)), s = std::sin(radians(rotationDeg));
  return {c * direction.x() + s * direction.y(), -s * direction.x() + c * direction.y(), direction.z()};
}

Vec3f Environment::radiance(const Vec3& direction) const {
  const Eigen::Vector2d uv = equirectFromDirection(imageFromWorld(direction));
  return strength * image->sample(uv.x(), uv.y());
}

}  // namespace omnicam
