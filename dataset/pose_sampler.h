#pragma once
// Robot poses of a dataset: a scene's named path, an explicit list, or seeded random sampling
// with clearance. Random sampling draws x, y, yaw from a 64-bit Mersenne Twister seeded with the
// spec's seed, turned into doubles by bit arithmetic (not std::uniform_real_distribution, whose
// output differs between standard libraries), so a seed gives the same poses everywhere.
#include <array>
#include <vector>

#include "dataset_spec.h"
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

// The robot poses the spec asks for. Random poses with a clearance are drawn uniformly from the
// region's free space (free_space.h), four draws per pose (triangle, two for the point, yaw);
// without a clearance, uniformly from the region (three draws). InputError naming the spec's
// field for a missing path, too few frames, or a region with no free space at that clearance.
std::vector<RobotPose> datasetPoses(const DatasetSpec& spec, const Scene& scene, double topHeight);

}  // namespace omnicam
