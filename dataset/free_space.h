#pragma once
// Where a robot of a given clearance can stand: the free-space polygon of a rectangular floor
// region, computed exactly with CGAL (Polygon_set_2 over an exact kernel). Every obstacle
// footprint (pose_sampler.h's FloorObstacles: objects rising above the floor, below the
// viewpoint) is grown by the clearance and cut out of the region; what remains is triangulated,
// and poses are drawn uniformly by area from those triangles — no rejection, so a crowded region
// costs nothing extra and an impossible one is known before the first draw.
//
// The growth is a Minkowski sum with a regular kDiscSides-gon *circumscribing* the clearance
// disc, so every point of the free space is at least `clearance` from every footprint (and at
// most clearance / cos(π / kDiscSides), 0.5 % more, where the polygon's corners stick out).
#include <array>
#include <vector>

#include "geometry.h"
#include "scene.h"

namespace omnicam {

struct FloorRegion {
  double xMin = 0.0, xMax = 0.0, yMin = 0.0, yMax = 0.0;
};

class FreeSpace {
 public:
  static constexpr int kDiscSides = 32;
  // `topHeight`: obstacles starting at or above it (a ceiling) do not block. Throws
  // std::invalid_argument for an empty region or a clearance outside [0, limits::kMaxLength].
  FreeSpace(const Scene& scene, double topHeight, const FloorRegion& region, double clearance);

  // Area of the free space in m².
  double area() const { return area_; }
  bool empty() const { return triangles_.empty(); }
  // Number of disjoint free areas (a maze's closed-off cells count separately).
  int componentCount() const { return components_; }
  // A point of the free space from three uniform draws in [0, 1): the first picks a triangle by
  // area, the other two a point in it. Uniform over the free space when the draws are.
  // Precondition: !empty().
  Vec2 pointFromDraws(double pickTriangle, double a, double b) const;

  // The triangulation (counter-clockwise triangles), for tests and plots.
  const std::vector<std::array<Vec2, 3>>& triangles() const { return triangles_; }

 private:
  std::vector<std::array<Vec2, 3>> triangles_;
  std::vector<double> cumulativeArea_;  // cumulativeArea_[k]: area of triangles 0..k
  double area_ = 0.0;
  int components_ = 0;
};

}  // namespace omnicam
