#include "pose_sampler.h"

#include <algorithm>
#include <random>

#include "errors.h"
#include "free_space.h"
#include "number_format.h"
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

// A uniform double in [0, 1) from 53 random bits: the same on every platform.
double unitDraw(std::mt19937_64& generator) { return static_cast<double>(generator() >> 11) * 0x1.0p-53; }

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

std::vector<RobotPose> datasetPoses(const DatasetSpec& spec, const Scene& scene, double topHeight) {
  switch (spec.poseSource) {
    case PoseSource::List:
      return spec.poseList;
    case PoseSource::Path: {
      const CameraPath* path = scene.findPath(spec.pathName);
      if (!path)
        throw InputError(showPath(spec.file) + ": poses.path: scene " + showPath(scene.path) + " has no path " + quote(spec.pathName));
      // Timed waypoints are all kept: "frames" then caps the frames taken along them.
      if (spec.timing.kind != PathTiming::Kind::None) return path->poses;
      if (spec.pathFrames > static_cast<int>(path->poses.size()))
        throw InputError(showPath(spec.file) + ": poses.frames: path " + quote(spec.pathName) + " has only " +
                         std::to_string(path->poses.size()) + " poses");
      const size_t n = spec.pathFrames ? spec.pathFrames : path->poses.size();
      checkFrameCount(spec, n, "poses.path");  // a whole path is only counted now
      return {path->poses.begin(), path->poses.begin() + n};
    }
    case PoseSource::Random: {
      const RandomPoses& r = spec.random;
      std::mt19937_64 generator(r.seed);
      std::vector<RobotPose> poses;
      if (r.clearance == 0.0) {
        for (int k = 0; k < r.count; ++k) {
          const double x = r.xMin + (r.xMax - r.xMin) * unitDraw(generator);
          const double y = r.yMin + (r.yMax - r.yMin) * unitDraw(generator);
          poses.push_back({x, y, r.yawMinDeg + (r.yawMaxDeg - r.yawMinDeg) * unitDraw(generator)});
        }
        return poses;
      }
      const FreeSpace free(scene, topHeight, {r.xMin, r.xMax, r.yMin, r.yMax}, r.clearance);
      if (free.empty())
        throw InputError(showPath(spec.file) + ": poses.random: no free space with " + shortNumber(r.clearance) +
                         " m clearance in the region [" + shortNumber(r.xMin) + ", " + shortNumber(r.xMax) + "] x [" +
                         shortNumber(r.yMin) + ", " + shortNumber(r.yMax) + "] m");
      for (int k = 0; k < r.count; ++k) {
        const double pick = unitDraw(generator), a = unitDraw(generator), b = unitDraw(generator);
        const Vec2 p = free.pointFromDraws(pick, a, b);
        poses.push_back({p.x(), p.y(), r.yawMinDeg + (r.yawMaxDeg - r.yawMinDeg) * unitDraw(generator)});
      }
      return poses;
    }
  }
  return {};
}

}  // namespace omnicam
