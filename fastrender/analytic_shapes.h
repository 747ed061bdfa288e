#pragma once
// Closed-form ray intersections for the curved primitives (double precision).
#include <optional>

#include "scene.h"

namespace omnicam {

struct ShapeHit {
  double t;
  Vec3 normal;  // unit, outward
  Eigen::Vector2d uv;
};

// Nearest hit with t ∈ (tNear, tFar), if any. `direction` need not be unit length.
std::optional<ShapeHit> intersect(const Sphere& s, const Vec3& o, const Vec3& d, double tNear, double tFar);
std::optional<ShapeHit> intersect(const Cylinder& c, const Vec3& o, const Vec3& d, double tNear, double tFar);
std::optional<ShapeHit> intersect(const Disc& disc, const Vec3& o, const Vec3& d, double tNear, double tFar);

// Axis-aligned bounds (lower, upper).
std::pair<Vec3, Vec3> bounds(const Sphere& s);
std::pair<Vec3, Vec3> bounds(const Cylinder& c);
std::pair<Vec3, Vec3> bounds(const Disc& d);

}  // namespace omnicam
