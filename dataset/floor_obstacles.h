#pragma once
#include <array>
#include <vector>

#include <Eigen/Geometry>

#include "geometry.h"
#include "scene.h"

namespace omnicam {

// A scene's obstacles seen from above: the XY footprints of every object that rises more than
// kObstacleMinHeight above the floor and starts below `topHeight` (the highest viewpoint), as
// triangles. Floors, floor markings and ceilings are not obstacles.
class FloorObstacles {
 public:
  static constexpr double kObstacleMinHeight = 0.01;
  // Curved shapes are tessellated with chords this close to the surface: footprints shrink by
  // at most this much, which clearance checks add back.
  static constexpr double kChordTolerance = 1e-3;
  struct Obstacle {
    Eigen::AlignedBox2d bounds;
    std::vector<std::array<Vec2, 3>> triangles;  // possibly degenerate (vertical faces)
  };
  FloorObstacles(const Scene& scene, double topHeight);
  // Distance in metres from (x, y) to the nearest footprint (0 inside one); `limit` if none is
  // nearer than `limit`.
  double distance(const Vec2& point, double limit) const;
  size_t obstacleCount() const { return obstacles_.size(); }
  const std::vector<Obstacle>& obstacles() const { return obstacles_; }

 private:
  std::vector<Obstacle> obstacles_;
};

}  // namespace omnicam
