#include "floor_obstacles.h"

#include <algorithm>
#include <cmath>

#include "triangulate.h"

namespace omnicam {

namespace {

constexpr double kChordTolerance = FloorObstacles::kChordTolerance;

double segmentDistance(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

double triangleDistance(const Vec2& p, const std::array<Vec2, 3>& t) {
  const double d0 = cross(t[1] - t[0], p - t[0]), d1 = cross(t[2] - t[1], p - t[1]), d2 = cross(t[0] - t[2], p - t[2]);
  const bool hasNegative = d0 < 0 || d1 < 0 || d2 < 0, hasPositive = d0 > 0 || d1 > 0 || d2 > 0;
  // Inside or on an edge — unless the triangle is degenerate (a wall's side seen from above is a
  // segment), where every point on its line has zero cross products and only the edges decide.
  if (!(hasNegative && hasPositive) && cross(t[1] - t[0], t[2] - t[0]) != 0.0) return 0.0;
  return std::min({segmentDistance(p, t[0], t[1]), segmentDistance(p, t[1], t[2]), segmentDistance(p, t[2], t[0])});
}

}  // namespace

FloorObstacles::FloorObstacles(const Scene& scene, double topHeight) {
  for (const SceneObject& object : scene.objects) {
    const TriangleMesh mesh = tessellate(object.shape, kChordTolerance);
    if (mesh.vertices.empty()) continue;
    double zMin = mesh.vertices[0].z(), zMax = zMin;
    for (const Vec3& v : mesh.vertices) zMin = std::min(zMin, v.z()), zMax = std::max(zMax, v.z());
    if (zMax <= kObstacleMinHeight || zMin >= topHeight) continue;
    Obstacle obstacle;
    for (const Eigen::Vector3i& tri : mesh.triangles) {
      std::array<Vec2, 3> t;
      for (int k = 0; k < 3; ++k) {
        t[k] = mesh.vertices[tri[k]].head<2>();
        obstacle.bounds.extend(t[k]);
      }
      obstacle.triangles.push_back(t);
    }
    obstacles_.push_back(std::move(obstacle));
  }
}

double FloorObstacles::distance(const Vec2& point, double limit) const {
  double best = limit;
  for (const Obstacle& o : obstacles_) {
    if (o.bounds.exteriorDistance(point) >= best) continue;
    for (const auto& t : o.triangles) best = std::min(best, triangleDistance(point, t));
    if (best == 0.0) return 0.0;
  }
  return best;
}

}  // namespace omnicam
